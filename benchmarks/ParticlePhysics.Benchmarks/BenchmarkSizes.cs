using System;
using System.Collections.Generic;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The cloth sizes the benchmarks run. The quick mode (CI) sets <see cref="QuickVariable"/> so that the parameter
/// sources give small cloths; an environment variable rather than a static field because BenchmarkDotNet's default
/// toolchain runs each benchmark in a child process, which inherits the environment.
/// </summary>
internal static class BenchmarkSizes
{
    public const string QuickVariable = "PARTICLEPHYSICS_BENCH_QUICK";

    /// <summary>The n x n cloth of the integrator comparison (issue 5): 64.</summary>
    public const int IntegratorCloth = 64;

    public static bool Quick => Environment.GetEnvironmentVariable(QuickVariable) == "1";

    /// <summary>n for the RK4 scaling benchmark: 16 to 256 (quick: 16 and 32).</summary>
    public static IEnumerable<int> Scaling => Quick ? new[] { 16, 32 } : new[] { 16, 32, 64, 128, 256 };

    /// <summary>n for the implicit Euler benchmarks (issues 3 and 13): 64 and 128 (quick: 16).</summary>
    public static IEnumerable<int> Implicit => Quick ? new[] { 16 } : new[] { 64, 128 };

    /// <summary>n for the one-core / two-core comparison (issue 5): 64 and 128 (quick: 16 and 48, above the parallel threshold).</summary>
    public static IEnumerable<int> Parallel => Quick ? new[] { 48 } : new[] { 64, 128 };

    /// <summary>n for the xpbd comparison with the C reference (issue 13): 32 to 256 (quick: 16).</summary>
    public static IEnumerable<int> Xpbd => Quick ? new[] { 16 } : new[] { 32, 64, 128, 256 };

    /// <summary>n for the comparisons with Math.NET and the student baseline: 32 and 128 (quick: 16).</summary>
    public static IEnumerable<int> Comparison => Quick ? new[] { 16 } : new[] { 32, 128 };
}
