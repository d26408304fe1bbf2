using System;
using System.Collections.Generic;
using System.Linq;
using ParticlePhysics.Demo.Output;
using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Demo.Plotting;

/// <summary>The heights against time: each computed curve solid with markers, its exact counterpart thin, dashed and on top.</summary>
internal sealed class TrajectoryPlot : IRunPlot
{
    private const int SmoothPoints = 400;
    private readonly ScenarioSetup _setup;
    private readonly RunPlan _plan;
    private readonly int[] _indices;
    private readonly List<double> _time = new();
    private readonly List<double>[] _values;

    public TrajectoryPlot(ScenarioSetup setup, RunPlan plan)
    {
        _setup = setup;
        _plan = plan;
        var columns = setup.Columns.ToList();
        _indices = setup.PlotSeries.Select(s => columns.IndexOf(s.Column)).ToArray();
        _values = _indices.Select(_ => new List<double>()).ToArray();
    }

    public bool Wants(int step) => _plan.IsOutputStep(step);

    public void Add(int step, double[] row)
    {
        _time.Add(row[0]);
        for (var i = 0; i < _indices.Length; i++)
        {
            _values[i].Add(row[_indices[i]]);
        }
    }

    public void Finish(RunOutcome outcome)
    {
    }

    public string ToSvg(RunOutcome outcome)
    {
        var title = $"{_setup.Name}: {_plan.Integrator}, dt = {Numbers.Brief(_plan.Dt)} s"
            + (outcome.Diverged is null ? string.Empty : $" (diverged at t = {Numbers.Brief(outcome.Diverged.Time)} s)");
        var chart = new LineChart(title, "t (s)", _setup is ScalarOdeSetup ? "y" : _setup.PlotAxisLabel);

        // The computed curves first, each with its own marker; then the exact ones on top of them, thin and dashed,
        // so that both show where they agree.
        var count = _time.Count;
        var every = count <= 40 ? 1 : (int)Math.Ceiling(count / 14.0);
        for (var s = 0; s < _setup.PlotSeries.Count; s++)
        {
            var column = _setup.PlotSeries[s].Column;
            var style = new SeriesStyle(LineChart.Palette[s % LineChart.Palette.Length], 2.6, null, LineChart.Markers[s % LineChart.Markers.Length], every, s * every / 2);
            chart.Add($"{column} ({_plan.Integrator})", _time, _values[s], style);
        }

        var end = count == 0 ? 0 : _time[^1];
        var times = Enumerable.Range(0, SmoothPoints + 1).Select(i => end * i / SmoothPoints).ToArray();
        foreach (var (column, exact) in _setup.PlotSeries)
        {
            if (exact is not null)
            {
                // On a fine grid of its own, so it stays smooth however few rows were printed.
                chart.Add($"{column} exact", times, times.Select(t => _setup.ExactValue(exact, t)).ToArray(), new SeriesStyle("#1a1a1a", 1.2, "5 3"));
            }
        }

        return chart.ToSvg();
    }
}
