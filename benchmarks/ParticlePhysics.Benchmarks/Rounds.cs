using System;
using System.Collections.Generic;
using System.Diagnostics;
using System.Linq;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// What the modes that alternate rounds outside BenchmarkDotNet (<c>xpbd</c>, <c>runner</c>) take of each round and
/// how they summarise the rounds: wall time and the process's CPU time, medians and medians of per-round ratios.
/// </summary>
internal static class Rounds
{
    /// <summary>Wall time and the process's CPU time of <paramref name="action"/>, in milliseconds.</summary>
    public static (double Wall, double Cpu) Time(Action action)
    {
        using var process = Process.GetCurrentProcess();
        var cpu = process.TotalProcessorTime;
        var clock = Stopwatch.StartNew();
        action();
        var wall = clock.Elapsed.TotalMilliseconds;
        process.Refresh();
        return (wall, (process.TotalProcessorTime - cpu).TotalMilliseconds);
    }

    /// <summary>The median of <paramref name="values"/> (the mean of the middle two for an even count).</summary>
    public static double Median(IReadOnlyList<double> values)
    {
        var sorted = values.OrderBy(x => x).ToArray();
        return sorted.Length % 2 == 1 ? sorted[sorted.Length / 2] : 0.5 * (sorted[(sorted.Length / 2) - 1] + sorted[sorted.Length / 2]);
    }

    /// <summary>The median over the rounds of numerator[r] / denominator[r].</summary>
    public static double MedianRatio(double[] numerator, double[] denominator) =>
        Median(numerator.Select((x, r) => x / denominator[r]).ToArray());
}
