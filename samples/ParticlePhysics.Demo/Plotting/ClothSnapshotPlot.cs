using System;
using System.Collections.Generic;
using System.Linq;
using ParticlePhysics.Demo.Output;
using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Demo.Plotting;

/// <summary>
/// Four snapshots of the cloth (t = 0, T/3, 2T/3 and the end), seen from the front: the x-y projection of its grid
/// lines, side by side on one scale, so the sag and the swing read at a glance. Large meshes are thinned to about
/// 40 grid lines each way to keep the file small.
/// </summary>
internal sealed class ClothSnapshotPlot : IRunPlot
{
    private const double PanelWidth = 230, PanelHeight = 260, Margin = 30, Top = 50;
    private readonly ClothSetup _setup;
    private readonly RunPlan _plan;
    private readonly List<Snapshot> _snapshots = new();
    private readonly int[] _steps;
    private Snapshot? _latest;

    public ClothSnapshotPlot(ClothSetup setup, RunPlan plan)
    {
        _setup = setup;
        _plan = plan;
        _steps = new[] { 0, (int)Math.Round(plan.Steps / 3.0), (int)Math.Round(2 * plan.Steps / 3.0), plan.Steps };
    }

    public bool Wants(int step) => Array.IndexOf(_steps, step) >= 0 || _plan.IsOutputStep(step);

    public void Add(int step, double[] row)
    {
        // Keep the snapshot steps, and the latest row in case the run diverges before its last snapshot.
        if (Array.IndexOf(_steps, step) >= 0 && _snapshots.All(s => s.Time != row[0]))
        {
            _snapshots.Add(Take(row));
            _latest = null;
        }
        else
        {
            _latest = Take(row);
        }
    }

    public void Finish(RunOutcome outcome)
    {
    }

    public string ToSvg(RunOutcome outcome)
    {
        var shots = _latest is null ? _snapshots : _snapshots.Append(_latest).ToList();
        var circle = _setup.Circle;
        var xs = shots.SelectMany(s => s.X).ToArray();
        var ys = shots.SelectMany(s => s.Y).ToArray();
        if (circle is { } c)
        {
            xs = xs.Append(c.X - c.Radius).Append(c.X + c.Radius).ToArray();
            ys = ys.Append(c.Y - c.Radius).Append(c.Y + c.Radius).ToArray();
        }

        double xMin = xs.Min(), xMax = xs.Max(), yMin = ys.Min(), yMax = ys.Max();
        var span = Math.Max(Math.Max(xMax - xMin, yMax - yMin), 1e-9);
        var scale = (Math.Min(PanelWidth, PanelHeight) - 20) / span;
        var width = (shots.Count * (PanelWidth + Margin)) + Margin;
        var svg = new SvgCanvas(width, Top + PanelHeight + 50);
        svg.Rect(0, 0, width, Top + PanelHeight + 50, "white");
        var title = $"{_setup.Name}, front view (x-y): {_setup.ParticlesPerSide} x {_setup.ParticlesPerSide} particles, {_plan.Integrator}, dt = {Numbers.Brief(_plan.Dt)} s"
            + (outcome.Diverged is null ? string.Empty : $", diverged at t = {Numbers.Brief(outcome.Diverged.Time)} s");
        svg.Text(width / 2, 24, title, "middle", 15, weight: "bold");
        var n = _setup.ParticlesPerSide;
        var stride = Math.Max(1, (int)Math.Ceiling(n / 40.0));
        for (var p = 0; p < shots.Count; p++)
        {
            var shot = shots[p];
            var left = Margin + (p * (PanelWidth + Margin));
            svg.Rect(left, Top, PanelWidth, PanelHeight, "#fafafa", "#999");
            double Px(double x) => left + 10 + ((x - xMin) * scale);
            double Py(double y) => Top + 10 + ((yMax - y) * scale);
            if (circle is { } sphere)
            {
                // The obstacle seen from the front, behind the mesh.
                svg.Polyline(Enumerable.Range(0, 97).Select(k => (Px(sphere.X + (sphere.Radius * Math.Cos(k * Math.PI / 48))), Py(sphere.Y + (sphere.Radius * Math.Sin(k * Math.PI / 48))))), "#999999", 1.5);
            }

            var lines = Enumerable.Range(0, n).Where(i => i % stride == 0 || i == n - 1).ToArray();
            foreach (var row in lines)
            {
                svg.Polyline(Enumerable.Range(0, n).Select(c => (Px(shot.X[(row * n) + c]), Py(shot.Y[(row * n) + c]))), LineChart.Palette[0], 1);
            }

            foreach (var col in lines)
            {
                svg.Polyline(Enumerable.Range(0, n).Select(r => (Px(shot.X[(r * n) + col]), Py(shot.Y[(r * n) + col]))), LineChart.Palette[1], 1);
            }

            svg.Text(left + (PanelWidth / 2), Top + PanelHeight + 20, $"t = {Numbers.Brief(shot.Time)} s", "middle", 13);
        }

        svg.Text(width / 2, Top + PanelHeight + 42, $"x from {Numbers.Brief(xMin)} to {Numbers.Brief(xMax)} m, y from {Numbers.Brief(yMin)} to {Numbers.Brief(yMax)} m (same scale on both axes)", "middle", 11);
        return svg.ToString();
    }

    private Snapshot Take(double[] row)
    {
        var count = _setup.ParticleCount;
        var x = new double[count];
        var y = new double[count];
        for (var i = 0; i < count; i++)
        {
            x[i] = row[1 + (6 * i)];
            y[i] = row[2 + (6 * i)];
        }

        return new Snapshot(row[0], x, y);
    }

    private sealed record Snapshot(double Time, double[] X, double[] Y);
}
