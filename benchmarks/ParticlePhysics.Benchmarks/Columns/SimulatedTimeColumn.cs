using System.Globalization;
using BenchmarkDotNet.Columns;
using BenchmarkDotNet.Reports;
using BenchmarkDotNet.Running;

namespace ParticlePhysics.Benchmarks.Columns;

/// <summary>
/// Computed columns of <see cref="IntegratorBenchmarks"/>: the time step used (the integrator's largest stable dt,
/// rounded down to whole steps per second) and the cost per simulated second (ms of wall time per second of cloth
/// time): the mean divided by dt for a one-step operation, or the mean itself for <c>SimulatedSecond</c>.
/// </summary>
internal sealed class SimulatedTimeColumn : IColumn
{
    private readonly bool _costColumn;

    private SimulatedTimeColumn(bool costColumn)
    {
        _costColumn = costColumn;
    }

    public static IColumn TimeStep { get; } = new SimulatedTimeColumn(false);

    public static IColumn CostPerSimulatedSecond { get; } = new SimulatedTimeColumn(true);

    public string Id => _costColumn ? "ms/sim-s" : "dt [s]";

    public string ColumnName => Id;

    public bool AlwaysShow => true;

    public ColumnCategory Category => ColumnCategory.Custom;

    public int PriorityInCategory => _costColumn ? 3 : 2;

    public bool IsNumeric => true;

    public UnitType UnitType => UnitType.Dimensionless;

    public string Legend => _costColumn
        ? "Wall-clock milliseconds per second of simulated time at dt"
        : "Time step: the largest stable dt of the integrator on the cloth (rk45: output interval)";

    public bool IsDefault(Summary summary, BenchmarkCase benchmarkCase) => false;

    public bool IsAvailable(Summary summary) => true;

    public string GetValue(Summary summary, BenchmarkCase benchmarkCase) =>
        GetValue(summary, benchmarkCase, summary.Style);

    public string GetValue(Summary summary, BenchmarkCase benchmarkCase, SummaryStyle style)
    {
        string? integrator = null;
        foreach (var parameter in benchmarkCase.Parameters.Items)
        {
            if (parameter.Name == nameof(IntegratorBenchmarks.Integrator))
            {
                integrator = parameter.Value as string;
            }
        }

        if (integrator is null || benchmarkCase.Descriptor.Type != typeof(IntegratorBenchmarks))
        {
            return "-";
        }

        var dt = IntegratorBenchmarks.TimeStepFor(integrator);
        if (!_costColumn)
        {
            return dt.ToString("G4", CultureInfo.InvariantCulture);
        }

        if (summary[benchmarkCase]?.ResultStatistics?.Mean is not double nanoseconds)
        {
            return "NA";
        }

        var perSimulatedSecond = benchmarkCase.Descriptor.WorkloadMethod.Name == nameof(IntegratorBenchmarks.SimulatedSecond)
            ? nanoseconds
            : nanoseconds / dt;
        return (perSimulatedSecond / 1e6).ToString("0.###", CultureInfo.InvariantCulture);
    }

    public override string ToString() => ColumnName;
}
