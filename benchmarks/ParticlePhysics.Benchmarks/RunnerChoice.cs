using System;
using System.Globalization;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// Which runner a mode uses: by default <see cref="WorkerThreadRunner"/> as the library ships it;
/// <c>--spin-us N</c>: the same with a spin limit of N microseconds (0: it never spins, every hand-off sleeps).
/// </summary>
internal static class RunnerChoice
{
    /// <summary>The runner the arguments name, with <paramref name="parallelism"/> threads (the caller's included).</summary>
    public static IParallelRunner Create(string[] args, int parallelism)
    {
        return SpinMicroseconds(args) is { } microseconds
            ? new WorkerThreadRunner(parallelism, TimeSpan.FromTicks((long)Math.Round(microseconds * 10)))
            : new WorkerThreadRunner(parallelism);
    }

    /// <summary>The name of the runner <see cref="Create"/> makes, for the output.</summary>
    public static string Describe(string[] args, int parallelism)
    {
        return SpinMicroseconds(args) is { } microseconds
            ? string.Create(CultureInfo.InvariantCulture, $"WorkerThreadRunner({parallelism}, spin limit {microseconds} us)")
            : $"WorkerThreadRunner({parallelism})";
    }

    private static double? SpinMicroseconds(string[] args)
    {
        var i = Array.IndexOf(args, "--spin-us");
        return i >= 0 && i + 1 < args.Length ? double.Parse(args[i + 1], CultureInfo.InvariantCulture) : null;
    }
}
