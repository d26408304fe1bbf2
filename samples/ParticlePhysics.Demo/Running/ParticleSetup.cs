using System;
using System.Collections.Generic;
using System.Globalization;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Demo.Running;

/// <summary>
/// The row layout of a particle scenario: <c>t</c>, then <c>x{i},y{i},z{i},vx{i},vy{i},vz{i}</c> per particle, then
/// the exact values of the vertical components (<c>y{i}_exact</c>, <c>vy{i}_exact</c>; or of another axis) and
/// <c>error</c> when there is an exact solution, then <c>energy</c> (kinetic + potential, J), for meshes <c>min_y</c> and <c>max_speed</c>,
/// then the scenario's own extra columns (a pendulum's angle and period, a chain's distance from its catenary).
/// </summary>
internal class ParticleSetup : ScenarioSetup, IParticleRun
{
    private readonly Func<ParticleWorld> _build;
    private readonly int _count;
    private readonly bool _meshColumns;
    private readonly int _exactAxis;
    private string[]? _columns;
    private readonly IReadOnlyList<ExtraColumn> _extras;
    private readonly Func<IStepObserver>? _observer;
    private double[] _exact = Array.Empty<double>();

    /// <param name="name">The scenario's name.</param>
    /// <param name="build">Builds a fresh system.</param>
    /// <param name="count">The number of particles the system has.</param>
    /// <param name="exact">The exact solution, or null.</param>
    /// <param name="meshColumns">Adds <c>min_y</c> and <c>max_speed</c> (for the cloth).</param>
    /// <param name="extras">Columns of the scenario's own, after all the others.</param>
    /// <param name="observer">Makes, for each run, what watches every step (a pendulum's period), or null.</param>
    /// <param name="exactAxis">The axis whose exact position and velocity get columns: 0 (x), 1 (y, the default) or 2 (z).</param>
    public ParticleSetup(
        string name,
        Func<ParticleWorld> build,
        int count,
        IExactSolution? exact,
        bool meshColumns = false,
        IReadOnlyList<ExtraColumn>? extras = null,
        Func<IStepObserver>? observer = null,
        int exactAxis = 1)
        : base(name, exact)
    {
        _exactAxis = exactAxis;
        _build = build;
        _extras = extras ?? Array.Empty<ExtraColumn>();
        _observer = observer;
        _meshColumns = meshColumns;
        _count = count;
    }

    /// <summary>
    /// The column names, made on first use (6 per particle: a large cloth's names take more memory than its world, so
    /// a run says what it costs before they exist).
    /// </summary>
    public override IReadOnlyList<string> Columns => _columns ??= ColumnNames();

    /// <summary>The number of columns, without making their names.</summary>
    public int ColumnCount => 1 + (6 * _count) + (Exact is null ? 0 : (2 * _count) + 1) + 1 + (_meshColumns ? 2 : 0) + _extras.Count;

    /// <summary>
    /// The bytes the column names take as .NET strings (22 bytes and 2 per character each, in 8-byte units), without
    /// making them: x{i}, y{i}, z{i} and vx{i}, vy{i}, vz{i} per particle, y{i}_exact and vy{i}_exact with an exact solution.
    /// </summary>
    public long ColumnNameBytes()
    {
        static long String(long length) => (22 + (2 * length) + 7) & ~7L;
        long bytes = 0;
        long first = 0;
        for (var digits = 1; first < _count; digits++)
        {
            // The particles whose index has this many digits: first to min(10 first, count) - 1 (10 when first is 0).
            var end = Math.Min(_count, first == 0 ? 10 : first * 10);
            var particles = end - first;
            bytes += particles * ((3 * String(1 + digits)) + (3 * String(2 + digits)));
            if (Exact is not null)
            {
                bytes += particles * (String(8 + digits) + String(9 + digits));
            }

            first = end;
        }

        // t, error, energy, min_y, max_speed (at most 9 characters) and the scenario's extra columns.
        bytes += 6 * String(9);
        foreach (var extra in _extras)
        {
            bytes += String(extra.Name.Length);
        }

        return bytes;
    }

    private string[] ColumnNames()
    {
        var columns = new List<string>(ColumnCount) { "t" };
        for (var i = 0; i < _count; i++)
        {
            foreach (var component in new[] { "x", "y", "z", "vx", "vy", "vz" })
            {
                columns.Add(Invariant($"{component}{i}"));
            }
        }

        if (Exact is not null)
        {
            var axis = "xyz"[_exactAxis];
            for (var i = 0; i < _count; i++)
            {
                columns.Add(Invariant($"{axis}{i}_exact"));
                columns.Add(Invariant($"v{axis}{i}_exact"));
            }

            columns.Add("error");
        }

        columns.Add("energy");
        if (_meshColumns)
        {
            columns.Add("min_y");
            columns.Add("max_speed");
        }

        foreach (var extra in _extras)
        {
            columns.Add(extra.Name);
        }

        return columns.ToArray();
    }

    public override IReadOnlyList<string> TableColumns => TableColumnList ?? Columns;

    public override IReadOnlyList<string> SummaryColumns => SummaryColumnList ?? Columns;

    public override IReadOnlyList<(string Column, string? Exact)> PlotSeries => PlotSeriesList;

    /// <summary>The columns of the table format.</summary>
    public IReadOnlyList<string>? TableColumnList { get; init; }

    /// <summary>The columns of the final-state summary.</summary>
    public IReadOnlyList<string>? SummaryColumnList { get; init; }

    /// <summary>The trajectory plot's curves.</summary>
    public IReadOnlyList<(string Column, string? Exact)> PlotSeriesList { get; init; } = Array.Empty<(string, string?)>();

    /// <summary>The number of particles.</summary>
    public int ParticleCount => _count;

    public override ISimulation CreateSimulation() => new ParticleSimulation(_build(), _observer?.Invoke());

    /// <summary>A fresh world at t = 0, as every run starts from (the replay reads its pins and springs).</summary>
    public ParticleWorld BuildWorld() => _build();

    /// <inheritdoc />
    public virtual int SurfaceSide => 0;

    /// <inheritdoc />
    public string? Subtitle => null;

    protected override void FillExact(double time, Span<double> row)
    {
        if (Exact is null)
        {
            return;
        }

        var exact = new double[6 * _count];
        Exact.ExactState(time, exact);
        var k = 1 + (6 * _count);
        for (var i = 0; i < _count; i++)
        {
            row[k++] = exact[(3 * i) + _exactAxis];
            row[k++] = exact[(3 * _count) + (3 * i) + _exactAxis];
        }
    }

    public override void FillRow(ISimulation simulation, double time, Span<double> row)
    {
        var particles = (ParticleSimulation)simulation;
        var system = particles.System;
        var positions = system.Positions;
        var velocities = system.Velocities;
        var k = 0;
        row[k++] = time;
        for (var i = 0; i < _count; i++)
        {
            for (var c = 0; c < 3; c++)
            {
                row[k++] = positions[(3 * i) + c];
            }

            for (var c = 0; c < 3; c++)
            {
                row[k++] = velocities[(3 * i) + c];
            }
        }

        if (Exact is not null)
        {
            var state = system.State;
            if (_exact.Length != state.Length)
            {
                _exact = new double[state.Length];
            }

            Exact.ExactState(time, _exact);
            for (var i = 0; i < _count; i++)
            {
                row[k++] = _exact[(3 * i) + _exactAxis];
                row[k++] = _exact[(3 * _count) + (3 * i) + _exactAxis];
            }

            row[k++] = MaxAbsDifference(state, _exact);
        }

        row[k++] = system.KineticEnergy() + system.PotentialEnergy();
        if (_meshColumns)
        {
            double minY = double.PositiveInfinity, maxSpeed = 0;
            for (var i = 0; i < _count; i++)
            {
                minY = Math.Min(minY, positions[(3 * i) + 1]);
                var v = velocities.Slice(3 * i, 3);
                maxSpeed = Math.Max(maxSpeed, Math.Sqrt((v[0] * v[0]) + (v[1] * v[1]) + (v[2] * v[2])));
            }

            row[k++] = minY;
            row[k++] = maxSpeed;
        }

        foreach (var extra in _extras)
        {
            row[k++] = extra.Value(particles);
        }
    }

    private static string Invariant(FormattableString text) => text.ToString(CultureInfo.InvariantCulture);
}
