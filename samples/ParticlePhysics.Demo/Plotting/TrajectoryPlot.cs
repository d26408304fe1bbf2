using System.Collections.Generic;
using System.Linq;
using ParticlePhysics.Demo.Output;
using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Demo.Plotting;

/// <summary>The heights against time, each computed curve solid and its exact counterpart dashed.</summary>
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
        _indices = setup.PlotSeries
            .SelectMany(s => s.Exact is null ? new[] { s.Column } : new[] { s.Column, s.Exact })
            .Select(c => columns.IndexOf(c))
            .ToArray();
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
        var k = 0;
        var markers = _time.Count <= 40;
        for (var s = 0; s < _setup.PlotSeries.Count; s++)
        {
            var (column, exact) = _setup.PlotSeries[s];
            var color = LineChart.Palette[s % LineChart.Palette.Length];
            chart.Add($"{column} ({_plan.Integrator})", _time, _values[k++], color, markers: markers);
            if (exact is not null)
            {
                // The exact curve on a fine grid of its own, so it stays smooth however few rows were printed.
                k++;
                var end = _time.Count == 0 ? 0 : _time[^1];
                var times = Enumerable.Range(0, SmoothPoints + 1).Select(i => end * i / SmoothPoints).ToArray();
                chart.Add($"{column} exact", times, times.Select(t => _setup.ExactValue(exact, t)).ToArray(), "#333333", dashed: true);
            }
        }

        return chart.ToSvg();
    }
}
