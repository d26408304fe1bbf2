using System;
using System.Diagnostics;
using System.Threading;
using ParticlePhysics.Parallel;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Parallel;

/// <summary>A run allocates nothing on any thread: the caller's, and each worker's, whether it spun or slept.</summary>
[Collection(AllocationMeasurements.Name)]
public class WorkerThreadRunnerAllocationTests
{
    [Theory]
    [InlineData(2, "adaptive")]
    [InlineData(3, "never-spin")]
    [InlineData(3, "always-spin-1us")]
    public void No_thread_allocates_per_run(int parallelism, string mode)
    {
        var random = new Random(7);
        var pauses = new int[20_000];
        for (var i = 0; i < pauses.Length; i++)
        {
            pauses[i] = random.Next(1000);
        }

        using var runner = WorkerThreadRunnerTests.Create(parallelism, mode);
        var probe = new AllocationProbe(parallelism);
        var work = new TinyWork();
        for (var i = 0; i < 1000; i++)
        {
            runner.Run(work, 1 + (i % (2 * parallelism)));
        }

        // Every thread's count over 20 000 runs, measured again when it is not zero, as ThreadAllocations.Measure does
        // (the runtime's per-thread count now and then reports bytes that were not allocated; see there).
        var counted = string.Empty;
        for (var attempt = 0; attempt < ThreadAllocations.Attempts; attempt++)
        {
            counted = CountOverRuns(runner, probe, work, pauses, parallelism);
            if (counted.Length == 0)
            {
                break;
            }
        }

        Assert.True(counted.Length == 0, counted);
    }

    /// <summary>
    /// Runs the work 20 000 times with the given pauses between runs; returns the bytes that the threads allocated over
    /// them ("" when none did). Each thread takes one chunk of a run that needs all of them at once, before and after,
    /// and notes its count.
    /// </summary>
    private static string CountOverRuns(WorkerThreadRunner runner, AllocationProbe probe, TinyWork work, int[] pauses, int parallelism)
    {
        probe.Reset(first: true);
        runner.Run(probe, parallelism);
        var callerBefore = GC.GetAllocatedBytesForCurrentThread();
        for (var i = 0; i < pauses.Length; i++)
        {
            runner.Run(work, 1 + (i % (2 * parallelism)));
            if (pauses[i] < 5)
            {
                Thread.Sleep(1); // long enough for the workers to go to sleep: the sleeping path runs too
            }
            else if (pauses[i] < 100)
            {
                Thread.SpinWait(pauses[i] * 20);
            }
        }

        var callerAllocated = GC.GetAllocatedBytesForCurrentThread() - callerBefore;
        probe.Reset(first: false);
        runner.Run(probe, parallelism);
        var counted = callerAllocated == 0 ? string.Empty : $"the caller: {callerAllocated} bytes; ";
        for (var t = 0; t < parallelism; t++)
        {
            Assert.True(probe.Thread[t] == probe.ThreadAfter[t], $"chunk {t} ran on two different threads");
            var bytes = probe.After[t] - probe.Before[t];
            counted += bytes == 0 ? string.Empty : $"the thread of chunk {t}: {bytes} bytes; ";
        }

        return counted;
    }

    private sealed class TinyWork : IParallelWork
    {
        private long _sum;

        public void Execute(int chunk, int chunkCount) => Interlocked.Add(ref _sum, chunk);
    }

    /// <summary>
    /// A run whose chunks wait for each other (so each thread takes exactly one) and note the thread's allocated
    /// bytes; chunk t is matched to the same thread in both runs through the thread's id.
    /// </summary>
    private sealed class AllocationProbe : IParallelWork
    {
        private readonly int _parties;
        private int _arrived;
        private bool _first;

        public AllocationProbe(int parties)
        {
            _parties = parties;
            Before = new long[parties];
            After = new long[parties];
            Thread = new int[parties];
            ThreadAfter = new int[parties];
        }

        public long[] Before { get; }

        public long[] After { get; }

        public int[] Thread { get; }

        public int[] ThreadAfter { get; }

        public void Reset(bool first)
        {
            _arrived = 0;
            _first = first;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var bytes = GC.GetAllocatedBytesForCurrentThread();
            var id = Environment.CurrentManagedThreadId;
            Interlocked.Increment(ref _arrived);
            var spinner = default(SpinWait);
            var start = Stopwatch.GetTimestamp();
            while (Volatile.Read(ref _arrived) < _parties)
            {
                if (Stopwatch.GetElapsedTime(start) > TimeSpan.FromSeconds(10))
                {
                    throw new TimeoutException($"chunk {chunk}: not every thread came");
                }

                spinner.SpinOnce(sleep1Threshold: -1);
            }

            if (_first)
            {
                Thread[chunk] = id;
                Before[chunk] = bytes;
                return;
            }

            // The second run may give this thread another chunk number: file it under the first run's.
            var slot = Array.IndexOf(Thread, id);
            ThreadAfter[slot < 0 ? chunk : slot] = id;
            After[slot < 0 ? chunk : slot] = bytes;
        }
    }
}
