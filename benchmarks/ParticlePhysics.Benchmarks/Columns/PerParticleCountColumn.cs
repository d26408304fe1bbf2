using System.Globalization;
using BenchmarkDotNet.Columns;
using BenchmarkDotNet.Reports;
using BenchmarkDotNet.Running;

namespace ParticlePhysics.Benchmarks.Columns;

/// <summary>The mean time per operation divided by the benchmark's <c>Particles</c> parameter, in nanoseconds.</summary>
internal sealed class PerParticleCountColumn : IColumn
{
    public static IColumn Instance { get; } = new PerParticleCountColumn();

    public string Id => "ns/particle";

    public string ColumnName => Id;

    public bool AlwaysShow => true;

    public ColumnCategory Category => ColumnCategory.Custom;

    public int PriorityInCategory => 0;

    public bool IsNumeric => true;

    public UnitType UnitType => UnitType.Dimensionless;

    public string Legend => "Mean time per particle per operation, in ns";

    public bool IsDefault(Summary summary, BenchmarkCase benchmarkCase) => false;

    public bool IsAvailable(Summary summary) => true;

    public string GetValue(Summary summary, BenchmarkCase benchmarkCase) => GetValue(summary, benchmarkCase, summary.Style);

    public string GetValue(Summary summary, BenchmarkCase benchmarkCase, SummaryStyle style)
    {
        var mean = summary[benchmarkCase]?.ResultStatistics?.Mean;
        foreach (var parameter in benchmarkCase.Parameters.Items)
        {
            if (parameter.Name == "Particles" && parameter.Value is int particles && mean is double nanoseconds)
            {
                return (nanoseconds / particles).ToString("0.###", CultureInfo.InvariantCulture);
            }
        }

        return "NA";
    }

    public override string ToString() => ColumnName;
}
