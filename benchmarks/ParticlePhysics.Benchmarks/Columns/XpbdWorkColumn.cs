using System.Globalization;
using BenchmarkDotNet.Columns;
using BenchmarkDotNet.Reports;
using BenchmarkDotNet.Running;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Benchmarks.Columns;

/// <summary>
/// Computed columns of the xpbd benchmarks, whose operation is one simulated second (60 frames of 1/60 s, 10 substeps
/// each): ms of wall time per simulated second (the mean itself), and ns per spring projection (the mean divided by
/// frames x substeps x <see cref="ClothScenario.SpringCount"/> of the N parameter): the flat measure across sizes.
/// </summary>
internal sealed class XpbdWorkColumn : IColumn
{
    private readonly bool _perProjection;

    private XpbdWorkColumn(bool perProjection)
    {
        _perProjection = perProjection;
    }

    public static IColumn PerSimulatedSecond { get; } = new XpbdWorkColumn(false);

    public static IColumn PerProjection { get; } = new XpbdWorkColumn(true);

    public string Id => _perProjection ? "ns/projection" : "ms/sim-s";

    public string ColumnName => Id;

    public bool AlwaysShow => true;

    public ColumnCategory Category => ColumnCategory.Custom;

    public int PriorityInCategory => _perProjection ? 1 : 0;

    public bool IsNumeric => true;

    public UnitType UnitType => UnitType.Dimensionless;

    public string Legend => _perProjection
        ? "Mean time per spring projection (60 frames x 10 substeps x springs per simulated second), in ns"
        : "Wall-clock milliseconds per second of simulated time (60 frames of 1/60 s)";

    public bool IsDefault(Summary summary, BenchmarkCase benchmarkCase) => false;

    public bool IsAvailable(Summary summary) => true;

    public string GetValue(Summary summary, BenchmarkCase benchmarkCase) => GetValue(summary, benchmarkCase, summary.Style);

    public string GetValue(Summary summary, BenchmarkCase benchmarkCase, SummaryStyle style)
    {
        if (summary[benchmarkCase]?.ResultStatistics?.Mean is not double nanoseconds)
        {
            return "NA";
        }

        if (!_perProjection)
        {
            return (nanoseconds / 1e6).ToString("0.###", CultureInfo.InvariantCulture);
        }

        var n = 0;
        foreach (var parameter in benchmarkCase.Parameters.Items)
        {
            if (parameter.Name == "N" && parameter.Value is int value)
            {
                n = value;
            }
        }

        if (n < 3)
        {
            return "-";
        }

        var projections = (double)XpbdCloth.StepsPerSecond * XpbdCloth.Substeps * ClothScenario.SpringCount(n);
        return (nanoseconds / projections).ToString("0.###", CultureInfo.InvariantCulture);
    }

    public override string ToString() => ColumnName;
}
