using System;

namespace ParticlePhysics.Tests.Support;

/// <summary>
/// The bytes the calling thread allocates in some repeatable work, by GC.GetAllocatedBytesForCurrentThread, measured
/// again when a count is not zero.
/// </summary>
/// <remarks>
/// The runtime's per-thread count now and then reports a few kilobytes where nothing was allocated: the runtime's own
/// test of that API fails so about once a week (dotnet/runtime#63487, "Allocated too much": 6232 and 10312 bytes
/// beyond a 1000-byte array), and here the same happened to steps that allocate nothing: 1576 bytes over 50 steps once
/// in CI, 6160 bytes over one implicit step on a runner in 2 of some 20 Debug runs of the suite, and one failure in the
/// CI run of 2026-12-03 (its test not recorded). None came back when the same steps were measured again. Work that
/// allocates each time it runs is counted every time and still fails; only a count that does not come back is
/// forgiven. The work must be safe to run <see cref="Attempts"/> times (a few more steps, frames or runs).
/// </remarks>
internal static class ThreadAllocations
{
    /// <summary>How many times the work is measured at most: once, and twice more if its count is not zero.</summary>
    public const int Attempts = 3;

    /// <summary>
    /// The bytes <paramref name="work"/> allocates on this thread: 0 as soon as one measurement counts none, otherwise
    /// the fewest of <see cref="Attempts"/> measurements.
    /// </summary>
    public static long Measure(Action work)
    {
        var fewest = long.MaxValue;
        for (var attempt = 0; attempt < Attempts; attempt++)
        {
            var before = GC.GetAllocatedBytesForCurrentThread();
            work();
            var bytes = GC.GetAllocatedBytesForCurrentThread() - before;
            if (bytes == 0)
            {
                return 0;
            }

            fewest = Math.Min(fewest, bytes);
        }

        return fewest;
    }
}
