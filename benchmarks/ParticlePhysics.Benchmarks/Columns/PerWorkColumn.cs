using System.Globalization;
using System.Reflection;
using BenchmarkDotNet.Columns;
using BenchmarkDotNet.Reports;
using BenchmarkDotNet.Running;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Benchmarks.Columns;

/// <summary>
/// A computed column: the mean time per operation divided by the cloth's particles, or by its spring evaluations
/// (springs x evaluations per operation, from <see cref="ClothWorkAttribute"/>). Always in nanoseconds, as a plain
/// number, so that the CSV export can be read by <c>benchmarks/plot.py</c> without parsing units.
/// </summary>
internal sealed class PerWorkColumn : IColumn
{
    private readonly bool _perSpringEvaluation;

    private PerWorkColumn(bool perSpringEvaluation)
    {
        _perSpringEvaluation = perSpringEvaluation;
    }

    /// <summary>Nanoseconds per particle per operation.</summary>
    public static IColumn PerParticle { get; } = new PerWorkColumn(false);

    /// <summary>Nanoseconds per spring evaluation.</summary>
    public static IColumn PerSpringEvaluation { get; } = new PerWorkColumn(true);

    public string Id => _perSpringEvaluation ? "ns/spring-eval" : "ns/particle";

    public string ColumnName => Id;

    public bool AlwaysShow => true;

    public ColumnCategory Category => ColumnCategory.Custom;

    public int PriorityInCategory => _perSpringEvaluation ? 1 : 0;

    public bool IsNumeric => true;

    public UnitType UnitType => UnitType.Dimensionless;

    public string Legend => _perSpringEvaluation
        ? "Mean time per spring evaluation (springs x force evaluations per operation), in ns"
        : "Mean time per particle per operation, in ns";

    public bool IsDefault(Summary summary, BenchmarkCase benchmarkCase) => false;

    public bool IsAvailable(Summary summary) => true;

    public string GetValue(Summary summary, BenchmarkCase benchmarkCase) =>
        GetValue(summary, benchmarkCase, summary.Style);

    public string GetValue(Summary summary, BenchmarkCase benchmarkCase, SummaryStyle style)
    {
        var work = benchmarkCase.Descriptor.WorkloadMethod.GetCustomAttribute<ClothWorkAttribute>();
        var mean = summary[benchmarkCase]?.ResultStatistics?.Mean;
        if (work is null)
        {
            return "-";
        }

        var n = ParticlesPerSide(benchmarkCase, work);
        if (mean is not double nanoseconds || n < 3)
        {
            return "NA";
        }

        var divisor = _perSpringEvaluation
            ? (double)ClothScenario.SpringCount(n) * work.EvaluationsPerOperation
            : (double)n * n;
        return (nanoseconds / divisor).ToString("0.###", CultureInfo.InvariantCulture);
    }

    public override string ToString() => ColumnName;

    private static int ParticlesPerSide(BenchmarkCase benchmarkCase, ClothWorkAttribute work)
    {
        foreach (var parameter in benchmarkCase.Parameters.Items)
        {
            if (parameter.Name == "N" && parameter.Value is int n)
            {
                return n;
            }
        }

        return work.ParticlesPerSide;
    }
}
