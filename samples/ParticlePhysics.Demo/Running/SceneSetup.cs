using System;
using System.Collections.Generic;
using System.Globalization;
using System.Text;
using ParticlePhysics.Demo.Output;
using ParticlePhysics.Forces;
using ParticlePhysics.Scenes;

namespace ParticlePhysics.Demo.Running;

/// <summary>
/// A scene file's run, with the contract's columns: <c>t</c>, then <c>x{i},y{i},z{i},vx{i},vy{i},vz{i}</c> for every
/// particle in numbering order, then <c>particles</c> (the count), <c>kinetic_energy</c> (sum of m v^2 / 2, J),
/// <c>min_y</c> and <c>max_speed</c>. Its json summary holds every particle's final position, velocity and mass.
/// </summary>
internal sealed class SceneSetup : ScenarioSetup, IParticleRun
{
    private readonly Scene _scene;
    private readonly double[] _masses;
    private readonly bool[] _pinned;
    private ParticleWorld? _first;
    private string[]? _columns;

    public SceneSetup(string name, Scene scene)
        : base(name, exact: null)
    {
        _scene = scene;

        // Built once now, so that a scene the core refuses fails before anything is printed, and so that the cost
        // estimate knows the springs; the first run takes this world.
        _first = scene.Build();
        ParticleCount = _first.Count;
        _masses = _first.Masses.ToArray();
        _pinned = new bool[ParticleCount];
        for (var i = 0; i < ParticleCount; i++)
        {
            _pinned[i] = _first.IsPinned(i);
        }

        foreach (var force in _first.Forces)
        {
            SpringCount += force switch
            {
                SpringNetwork springs => springs.Count + springs.AnchoredCount,
                ZeroLengthSprings springs => springs.Count + springs.AnchoredCount,
                _ => 0,
            };
        }

        Subtitle = Describe(scene);
    }

    /// <summary>The scene.</summary>
    public Scene Scene => _scene;

    public int ParticleCount { get; }

    /// <summary>The springs of all kinds, for the cost estimate.</summary>
    public long SpringCount { get; }

    public int SurfaceSide => 0;

    public string? Subtitle { get; }

    public override string JsonNameKey => "scene";

    public override bool HasParameters => false;

    public override IReadOnlyList<string> Columns => _columns ??= ColumnNames();

    public override IReadOnlyList<string> TableColumns { get; } = new[] { "t", "kinetic_energy", "min_y", "max_speed" };

    public override IReadOnlyList<string> SummaryColumns { get; } = new[] { "kinetic_energy", "min_y", "max_speed" };

    /// <summary>The heights of the first few particles that move (pinned ones never do), or the lowest one of many.</summary>
    public override IReadOnlyList<(string Column, string? Exact)> PlotSeries
    {
        get
        {
            var series = new List<(string, string?)>();
            for (var i = 0; i < ParticleCount && series.Count < 6; i++)
            {
                if (!_pinned[i])
                {
                    series.Add((Invariant($"y{i}"), null));
                }
            }

            return series.Count < ParticleCount - CountPinned() ? new (string, string?)[] { ("min_y", null) } : series;
        }
    }

    public ParticleWorld BuildWorld() => _scene.Build();

    public override ISimulation CreateSimulation()
    {
        var world = _first ?? _scene.Build();
        _first = null;
        return new ParticleSimulation(world);
    }

    public override void FillRow(ISimulation simulation, double time, Span<double> row)
    {
        var world = ((ParticleSimulation)simulation).System;
        var x = world.Positions;
        var v = world.Velocities;
        var n = ParticleCount;
        var k = 0;
        row[k++] = time;
        double kinetic = 0, minY = double.PositiveInfinity, maxSpeed = 0;
        for (var i = 0; i < n; i++)
        {
            var o = 3 * i;
            row[k++] = x[o];
            row[k++] = x[o + 1];
            row[k++] = x[o + 2];
            row[k++] = v[o];
            row[k++] = v[o + 1];
            row[k++] = v[o + 2];
            var speedSquared = (v[o] * v[o]) + (v[o + 1] * v[o + 1]) + (v[o + 2] * v[o + 2]);
            kinetic += 0.5 * _masses[i] * speedSquared;
            minY = Math.Min(minY, x[o + 1]);
            maxSpeed = Math.Max(maxSpeed, Math.Sqrt(speedSquared));
        }

        row[k++] = n;
        row[k++] = kinetic;
        row[k++] = minY;
        row[k] = maxSpeed;
    }

    /// <summary>The json summary's final: every particle's position, velocity and mass, from the last good row.</summary>
    public override string FinalJson(RunOutcome outcome)
    {
        var row = outcome.FinalRow;
        var text = new StringBuilder("{ \"positions\": [");
        for (var i = 0; i < ParticleCount; i++)
        {
            var o = 1 + (6 * i);
            text.Append(i == 0 ? "[" : ", [").Append(Numbers.Json(row[o])).Append(", ").Append(Numbers.Json(row[o + 1])).Append(", ").Append(Numbers.Json(row[o + 2])).Append(']');
        }

        text.Append("], \"velocities\": [");
        for (var i = 0; i < ParticleCount; i++)
        {
            var o = 4 + (6 * i);
            text.Append(i == 0 ? "[" : ", [").Append(Numbers.Json(row[o])).Append(", ").Append(Numbers.Json(row[o + 1])).Append(", ").Append(Numbers.Json(row[o + 2])).Append(']');
        }

        text.Append("], \"masses\": [");
        for (var i = 0; i < ParticleCount; i++)
        {
            text.Append(i == 0 ? string.Empty : ", ").Append(Numbers.Json(_masses[i]));
        }

        return text.Append("] }").ToString();
    }

    protected override void FillExact(double time, Span<double> row)
    {
    }

    private int CountPinned() => Array.FindAll(_pinned, p => p).Length;

    private string[] ColumnNames()
    {
        var columns = new List<string>((6 * ParticleCount) + 5) { "t" };
        for (var i = 0; i < ParticleCount; i++)
        {
            foreach (var component in new[] { "x", "y", "z", "vx", "vy", "vz" })
            {
                columns.Add(component + i.ToString(CultureInfo.InvariantCulture));
            }
        }

        columns.AddRange(new[] { "particles", "kinetic_energy", "min_y", "max_speed" });
        return columns.ToArray();
    }

    private static string Describe(Scene scene)
    {
        var kinds = new List<string>();
        foreach (var kind in scene.ObjectKinds)
        {
            if (!kinds.Contains(kind))
            {
                kinds.Add(kind);
            }
        }

        foreach (var kind in scene.ColliderKinds)
        {
            var collider = kind + " collider";
            if (!kinds.Contains(collider))
            {
                kinds.Add(collider);
            }
        }

        return Invariant($"{scene.ParticleCount} particles; ") + string.Join(", ", kinds)
            + (scene.Settings.ParticleCollisions ? "; particle collisions" : string.Empty);
    }

    private static string Invariant(FormattableString text) => text.ToString(CultureInfo.InvariantCulture);
}
