using System.Collections.Concurrent;
using System.Globalization;
using BenchmarkDotNet.Columns;
using BenchmarkDotNet.Reports;
using BenchmarkDotNet.Running;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Benchmarks.Columns;

/// <summary>
/// Computed columns of <see cref="ImplicitEulerBenchmarks"/>: the conjugate-gradient iterations per step (counted by
/// running the same simulated second in the host process: deterministic, so the same as in the measured run) and
/// the mean divided by the iterations of the second (the cost of one iteration with its share of the per-step work).
/// </summary>
internal sealed class ImplicitIterationsColumn : IColumn
{
    private static readonly ConcurrentDictionary<(int, double, ImplicitPreconditioner), double> _iterations = new();
    private readonly bool _perIteration;

    private ImplicitIterationsColumn(bool perIteration)
    {
        _perIteration = perIteration;
    }

    public static IColumn IterationsPerStep { get; } = new ImplicitIterationsColumn(false);

    public static IColumn MicrosecondsPerIteration { get; } = new ImplicitIterationsColumn(true);

    public string Id => _perIteration ? "us/CG it" : "CG it/step";

    public string ColumnName => Id;

    public bool AlwaysShow => true;

    public ColumnCategory Category => ColumnCategory.Custom;

    public int PriorityInCategory => _perIteration ? 2 : 1;

    public bool IsNumeric => true;

    public UnitType UnitType => UnitType.Dimensionless;

    public string Legend => _perIteration
        ? "Mean divided by the CG iterations of the simulated second (each iteration's share of the whole step, setup included)"
        : "Conjugate-gradient iterations per step, mean over the simulated second";

    public bool IsDefault(Summary summary, BenchmarkCase benchmarkCase) => false;

    public bool IsAvailable(Summary summary) => true;

    public string GetValue(Summary summary, BenchmarkCase benchmarkCase) => GetValue(summary, benchmarkCase, summary.Style);

    public string GetValue(Summary summary, BenchmarkCase benchmarkCase, SummaryStyle style)
    {
        if (benchmarkCase.Descriptor.Type != typeof(ImplicitEulerBenchmarks))
        {
            return "-";
        }

        int n = 0;
        double tolerance = 0;
        var preconditioner = ImplicitPreconditioner.Multigrid;
        foreach (var parameter in benchmarkCase.Parameters.Items)
        {
            switch (parameter.Name)
            {
                case nameof(ImplicitEulerBenchmarks.N):
                    n = (int)parameter.Value;
                    break;
                case nameof(ImplicitEulerBenchmarks.Tolerance):
                    tolerance = (double)parameter.Value;
                    break;
                case nameof(ImplicitEulerBenchmarks.Preconditioner):
                    preconditioner = (ImplicitPreconditioner)parameter.Value;
                    break;
            }
        }

        var iterations = _iterations.GetOrAdd((n, tolerance, preconditioner), key => ImplicitEulerBenchmarks.MeanIterations(key.Item1, key.Item2, key.Item3));
        if (!_perIteration)
        {
            return iterations.ToString("0.00", CultureInfo.InvariantCulture);
        }

        if (summary[benchmarkCase]?.ResultStatistics?.Mean is not double nanoseconds)
        {
            return "NA";
        }

        return (nanoseconds / 1e3 / (60 * iterations)).ToString("0.0", CultureInfo.InvariantCulture);
    }

    public override string ToString() => ColumnName;
}
