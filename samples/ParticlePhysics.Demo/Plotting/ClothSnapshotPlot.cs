using System;
using System.Collections.Generic;
using System.Globalization;
using System.Linq;
using ParticlePhysics.Contacts;
using ParticlePhysics.Demo.Output;
using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Demo.Plotting;

/// <summary>
/// Snapshots of the cloth (t = 0, T/3, 2T/3 and the end, or the last good state of a diverged run) in two rows:
/// seen from the front (the x-y projection of its grid lines, with axes in metres, one scale for all and equal on
/// both axes), and in perspective (a shaded surface, front and back in two colours, over a floor grid at its lowest
/// point). Pinned particles are marked in both, and the world's sphere obstacles (the drape's) are drawn in both,
/// read from its contact sets. Large meshes are thinned to about 40 grid lines each way in front
/// and 24 in perspective, to keep the file small. A snapshot that has blown up (a diverged run's last ones) gets a
/// scale of its own, said under it, so that the others keep theirs.
/// </summary>
internal sealed class ClothSnapshotPlot : IRunPlot
{
    private const double Panel = 220, AxisLeft = 50, AxisBottom = 34, Gap = 22, Margin = 16, Top = 64, TitleSize = 15;
    private const double Yaw = 0.6, Pitch = 0.32;
    private const string PinColor = "#C62828";
    private static readonly (int R, int G, int B) _front = (70, 125, 180);
    private static readonly (int R, int G, int B) _back = (214, 146, 60);
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
        // Keep the snapshot steps, and the latest row in case the run stops before its last snapshot.
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
        if (_snapshots.All(s => s.Time != outcome.FinalTime))
        {
            _latest = Take(outcome.FinalRow);
        }
    }

    public string ToSvg(RunOutcome outcome)
    {
        var shots = _latest is null ? _snapshots : _snapshots.Append(_latest).ToList();
        var n = _setup.ParticlesPerSide;
        var world = _setup.BuildWorld();
        var pinned = Enumerable.Range(0, world.Count).Where(world.IsPinned).ToArray();
        var spheres = world.Constraints.OfType<ContactSet>().SelectMany(set => set.Obstacles)
            .Select(o => o.ShapeAt(0)).Where(shape => shape.Kind == ObstacleKind.Sphere).ToArray();

        // One scale for the snapshots that have not blown up (within 5 times the first one's size).
        var first = Extent(shots[0]);
        var shared = shots.Where(s => Extent(s) <= 5 * Math.Max(first, 1e-9)).ToList();
        var (low, high) = Bounds(shared);
        foreach (var sphere in spheres)
        {
            // The obstacles are part of the picture: the window holds them too.
            var reach = new Vector3d(sphere.Radius, sphere.Radius, sphere.Radius);
            var (a, b) = (sphere.Center - reach, sphere.Center + reach);
            low = new Vector3d(Math.Min(low.X, a.X), Math.Min(low.Y, a.Y), Math.Min(low.Z, a.Z));
            high = new Vector3d(Math.Max(high.X, b.X), Math.Max(high.Y, b.Y), Math.Max(high.Z, b.Z));
        }

        var title = $"{_setup.Name}: {n} x {n} particles, {_plan.Integrator}, dt = {Numbers.Brief(_plan.Dt)} s"
            + (outcome.Diverged is null ? string.Empty : $", diverged at t = {Numbers.Brief(outcome.Diverged.Time)} s")
            + (outcome.Interrupted ? $", interrupted at t = {Numbers.Brief(outcome.FinalTime)} s" : string.Empty);
        var column = AxisLeft + Panel + Gap;
        var width = Math.Max((2 * Margin) + (shots.Count * column), SvgCanvas.TextWidth(title, TitleSize, bold: true) + 40);
        var left0 = (width - (shots.Count * column)) / 2;
        var frontTop = Top;
        var perspectiveTop = frontTop + Panel + AxisBottom + 48;
        var height = perspectiveTop + Panel + 62;
        var svg = new SvgCanvas(width, height);
        svg.Rect(0, 0, width, height, "white");
        svg.Text(width / 2, 26, title, "middle", TitleSize, weight: "bold");
        var obstacle = spheres.Length == 0 ? string.Empty : spheres.Length == 1 ? "; the sphere in grey" : "; the spheres in grey";
        svg.Text(width / 2, 46, "front view (x-y), one scale, equal on both axes" + (pinned.Length > 0 ? "; pinned particles in red" : string.Empty) + obstacle, "middle", 12, fill: "#444");
        svg.Text(width / 2, perspectiveTop - 12, "perspective view: the surface, front side blue, back side orange, over a floor grid" + obstacle, "middle", 12, fill: "#444");

        var camera = OrbitProjection.Fitting(low, high, Yaw, Pitch);
        for (var p = 0; p < shots.Count; p++)
        {
            var shot = shots[p];
            var own = !shared.Contains(shot);
            var (lo, hi) = own ? Bounds(new[] { shot }) : (low, high);
            var x = left0 + (p * column) + AxisLeft;
            FrontPanel(svg, shot, pinned, n, x, frontTop, lo, hi, own ? Array.Empty<ObstacleShape>() : spheres);
            var label = $"t = {Numbers.Brief(shot.Time)} s" + (own ? " (own scale: blown up)" : string.Empty);
            svg.Text(x + (Panel / 2), frontTop + Panel + AxisBottom + 4, label, "middle", 13, fill: own ? PinColor : "#222");
            PerspectivePanel(svg, shot, pinned, n, x, perspectiveTop, own ? OrbitProjection.Fitting(lo, hi, Yaw, Pitch) : camera, lo, hi, own ? Array.Empty<ObstacleShape>() : spheres);
            svg.Text(x + (Panel / 2), perspectiveTop + Panel + 20, label, "middle", 13, fill: own ? PinColor : "#222");
        }

        svg.Text(width / 2, height - 14, $"x from {Numbers.Brief(low.X)} to {Numbers.Brief(high.X)} m, y from {Numbers.Brief(low.Y)} to {Numbers.Brief(high.Y)} m, z from {Numbers.Brief(low.Z)} to {Numbers.Brief(high.Z)} m", "middle", 11, fill: "#444");
        return svg.ToString();
    }

    private static void FrontPanel(SvgCanvas svg, Snapshot shot, int[] pinned, int n, double left, double top, Vector3d low, Vector3d high, ObstacleShape[] spheres)
    {
        // A square window on the x-y extent, so that one metre is as long across as up.
        var span = Math.Max(Math.Max(high.X - low.X, high.Y - low.Y), 1e-9) * 1.08;
        double cx = 0.5 * (low.X + high.X), cy = 0.5 * (low.Y + high.Y);
        double x0 = cx - (span / 2), y0 = cy - (span / 2);
        double Px(double x) => left + ((x - x0) / span * Panel);
        double Py(double y) => top + Panel - ((y - y0) / span * Panel);
        svg.Rect(left, top, Panel, Panel, "#fbfbfb", "#999");
        foreach (var t in FittingTicks(x0, x0 + span))
        {
            svg.Line(Px(t), top, Px(t), top + Panel, "#ececec");
            svg.Line(Px(t), top + Panel, Px(t), top + Panel + 4, "#333");
            svg.Text(Px(t), top + Panel + 15, Tick(t), "middle", 10);
        }

        foreach (var t in Axis.LinearTicks(y0, y0 + span, 4))
        {
            svg.Line(left, Py(t), left + Panel, Py(t), "#ececec");
            svg.Line(left - 4, Py(t), left, Py(t), "#333");
            svg.Text(left - 6, Py(t) + 3.5, Tick(t), "end", 10);
        }

        svg.Text(left + Panel - 2, top + Panel + 28, "x (m)", "end", 10, fill: "#444");
        svg.Text(left - 6, top - 6, "y (m)", "end", 10, fill: "#444");
        svg.BeginClip(left, top, Panel, Panel);
        foreach (var sphere in spheres)
        {
            // The obstacle seen from the front, behind the mesh.
            var (sx, sy, sr) = (sphere.Center.X, sphere.Center.Y, sphere.Radius);
            svg.Polyline(Enumerable.Range(0, 97).Select(k => (Px(sx + (sr * Math.Cos(k * Math.PI / 48))), Py(sy + (sr * Math.Sin(k * Math.PI / 48))))), "#999999", 1.5);
        }

        var lines = Thinned(n, 40);
        foreach (var row in lines)
        {
            svg.Polyline(Enumerable.Range(0, n).Select(c => (Px(shot.X[(row * n) + c]), Py(shot.Y[(row * n) + c]))), LineChart.Palette[0], 1);
        }

        foreach (var col in lines)
        {
            svg.Polyline(Enumerable.Range(0, n).Select(r => (Px(shot.X[(r * n) + col]), Py(shot.Y[(r * n) + col]))), LineChart.Palette[1], 1);
        }

        foreach (var i in pinned)
        {
            svg.Rect(Px(shot.X[i]) - 4, Py(shot.Y[i]) - 4, 8, 8, PinColor);
        }

        svg.EndGroup();
    }

    private static void PerspectivePanel(SvgCanvas svg, Snapshot shot, int[] pinned, int n, double left, double top, OrbitProjection camera, Vector3d low, Vector3d high, ObstacleShape[] spheres)
    {
        svg.Rect(left, top, Panel, Panel, "#f6f7f9", "#999");

        // The image of the whole box fills the panel (the same for every snapshot that shares the camera).
        var corners = Enumerable.Range(0, 8).Select(k => camera.Project(new Vector3d(
            (k & 1) == 0 ? low.X : high.X, (k & 2) == 0 ? low.Y : high.Y, (k & 4) == 0 ? low.Z : high.Z))).ToArray();
        double u0 = corners.Min(c => c.X), u1 = corners.Max(c => c.X), v0 = corners.Min(c => c.Y), v1 = corners.Max(c => c.Y);
        var scale = 0.92 * Panel / Math.Max(Math.Max(u1 - u0, v1 - v0), 1e-12);
        double uc = 0.5 * (u0 + u1), vc = 0.5 * (v0 + v1);
        (double X, double Y, double Depth) Screen(Vector3d p)
        {
            var (u, v, depth) = camera.Project(p);
            return (left + (Panel / 2) + ((u - uc) * scale), top + (Panel / 2) - ((v - vc) * scale), depth);
        }

        svg.BeginClip(left, top, Panel, Panel);

        // The floor: a grid at the lowest point, a little wider than the cloth.
        var span = Math.Max(Math.Max(high.X - low.X, high.Z - low.Z), 1e-9);
        var step = Axis.NiceStep(span / 5);
        var (gx0, gx1) = (Math.Floor((low.X - (0.2 * span)) / step) * step, Math.Ceiling((high.X + (0.2 * span)) / step) * step);
        var (gz0, gz1) = (Math.Floor((low.Z - (0.2 * span)) / step) * step, Math.Ceiling((high.Z + (0.2 * span)) / step) * step);
        for (var g = gx0; g <= gx1 + (1e-9 * step); g += step)
        {
            var (a, b) = (Screen(new Vector3d(g, low.Y, gz0)), Screen(new Vector3d(g, low.Y, gz1)));
            svg.Line(a.X, a.Y, b.X, b.Y, "#d9dde2");
        }

        for (var g = gz0; g <= gz1 + (1e-9 * step); g += step)
        {
            var (a, b) = (Screen(new Vector3d(gx0, low.Y, g)), Screen(new Vector3d(gx1, low.Y, g)));
            svg.Line(a.X, a.Y, b.X, b.Y, "#d9dde2");
        }

        // The surface: the thinned grid's quads, farthest first, each shaded by its normal against a light over the
        // viewer's left shoulder, and outlined (the grid lines).
        var lines = Thinned(n, 24);
        var light = camera.Up - (0.5 * camera.Right) - camera.Forward;
        light /= light.Length;
        var quads = new List<(double Depth, (double X, double Y)[] Points, string Fill, bool Behind)>();
        for (var r = 0; r + 1 < lines.Length; r++)
        {
            for (var c = 0; c + 1 < lines.Length; c++)
            {
                var ids = new[] { (lines[r] * n) + lines[c], (lines[r] * n) + lines[c + 1], (lines[r + 1] * n) + lines[c + 1], (lines[r + 1] * n) + lines[c] };
                var world = ids.Select(shot.At).ToArray();
                var normal = Vector3d.Cross(world[3] - world[0], world[1] - world[0]);
                var length = normal.Length;
                if (!(length > 0))
                {
                    continue;
                }

                normal /= length;
                var screen = world.Select(Screen).ToArray();
                var facing = Vector3d.Dot(camera.Eye - world[0], normal) > 0; // the side the normal (+y at the start) points to

                var lit = 0.38 + (0.76 * Math.Abs(Vector3d.Dot(normal, light)));
                var rgb = facing ? _front : _back;
                var middle = 0.25 * (world[0] + world[1] + world[2] + world[3]);
                quads.Add((screen.Average(s => s.Depth), screen.Select(s => (s.X, s.Y)).ToArray(), Shade(rgb, lit), Hidden(middle)));
            }
        }

        // A sphere is a disc; a quad whose centre it hides from the eye (the ray to the centre meets the sphere
        // first) is drawn before it, every other quad after it, each group farthest first.
        bool Hidden(Vector3d point) => spheres.Any(sphere => HiddenBy(sphere, camera.Eye, point));
        var ordered = quads.OrderByDescending(q => q.Depth).ToList();
        foreach (var (_, points, fill, _) in ordered.Where(q => q.Behind))
        {
            svg.Polygon(points, fill, "rgba(20,35,55,0.35)", 0.6);
        }

        foreach (var sphere in spheres)
        {
            var (cx, cy, depth) = Screen(sphere.Center);
            if (depth > 0)
            {
                var r = Math.Abs(Screen(sphere.Center + (sphere.Radius * camera.Right)).X - cx);
                svg.Circle(cx, cy, r, "rgb(150,158,168)", "rgb(110,116,124)", 0.8);
                svg.Circle(cx - (0.3 * r), cy - (0.3 * r), 0.45 * r, "rgba(255,255,255,0.35)");
            }
        }

        foreach (var (_, points, fill, _) in ordered.Where(q => !q.Behind))
        {
            svg.Polygon(points, fill, "rgba(20,35,55,0.35)", 0.6);
        }

        foreach (var i in pinned)
        {
            var (x, y, _) = Screen(shot.At(i));
            svg.Rect(x - 4, y - 4, 8, 8, PinColor);
        }

        svg.EndGroup();
        Triad(svg, camera, left + 22, top + Panel - 20);
    }

    /// <summary>
    /// Whether <paramref name="sphere"/> stands between <paramref name="eye"/> and <paramref name="point"/>: the ray
    /// eye + s d (d the unit direction to the point, s from 0 to the point's distance L) meets the sphere where
    /// |eye + s d - c|^2 = R^2, s = b - sqrt(b^2 - |eye - c|^2 + R^2) with b = d . (c - eye), when 0 &lt; s &lt; L.
    /// </summary>
    private static bool HiddenBy(ObstacleShape sphere, Vector3d eye, Vector3d point)
    {
        var to = point - eye;
        var length = to.Length;
        if (!(length > 0))
        {
            return false;
        }

        var d = to / length;
        var b = Vector3d.Dot(d, sphere.Center - eye);
        var discriminant = (b * b) - (sphere.Center - eye).LengthSquared + (sphere.Radius * sphere.Radius);
        if (discriminant < 0)
        {
            return false;
        }

        var s = b - Math.Sqrt(discriminant);
        return s > 0 && s < length - (1e-9 * length);
    }

    /// <summary>The world axes as seen by the camera: x red, y green, z blue.</summary>
    private static void Triad(SvgCanvas svg, OrbitProjection camera, double x, double y)
    {
        var axes = new[] { (new Vector3d(1, 0, 0), "#C62828", "x"), (new Vector3d(0, 1, 0), "#2E7D32", "y"), (new Vector3d(0, 0, 1), "#1565C0", "z") };
        foreach (var (axis, color, name) in axes)
        {
            double dx = Vector3d.Dot(axis, camera.Right), dy = Vector3d.Dot(axis, camera.Up);
            svg.Line(x, y, x + (14 * dx), y - (14 * dy), color, 1.6);
            svg.Text(x + (20 * dx), y - (20 * dy) + 3.5, name, "middle", 9, fill: color);
        }
    }

    private static string Shade((int R, int G, int B) rgb, double k) => string.Create(
        CultureInfo.InvariantCulture, $"rgb({Math.Min(255, (int)(rgb.R * k))},{Math.Min(255, (int)(rgb.G * k))},{Math.Min(255, (int)(rgb.B * k))})");

    private static string Tick(double value) => value.ToString("G4", CultureInfo.InvariantCulture);

    // Ticks along x whose labels do not run into each other (fewer of them when the numbers are long).
    private static double[] FittingTicks(double low, double high)
    {
        for (var count = 4; ; count--)
        {
            var ticks = Axis.LinearTicks(low, high, count);
            var widest = ticks.Max(t => SvgCanvas.TextWidth(Tick(t), 10));
            if (count == 1 || (ticks.Length * (widest + 14)) <= Panel)
            {
                return ticks;
            }
        }
    }

    private static int[] Thinned(int n, int most)
    {
        var stride = Math.Max(1, (int)Math.Ceiling(n / (double)most));
        return Enumerable.Range(0, n).Where(i => i % stride == 0 || i == n - 1).ToArray();
    }

    private static double Extent(Snapshot shot)
    {
        var (lo, hi) = Bounds(new[] { shot });
        return Math.Max(hi.X - lo.X, Math.Max(hi.Y - lo.Y, hi.Z - lo.Z));
    }

    private static (Vector3d Low, Vector3d High) Bounds(IEnumerable<Snapshot> shots)
    {
        var list = shots.ToList();
        double Min(Func<Snapshot, double[]> axis) => list.Min(s => axis(s).Min());
        double Max(Func<Snapshot, double[]> axis) => list.Max(s => axis(s).Max());
        return (new Vector3d(Min(s => s.X), Min(s => s.Y), Min(s => s.Z)), new Vector3d(Max(s => s.X), Max(s => s.Y), Max(s => s.Z)));
    }

    private Snapshot Take(double[] row)
    {
        var count = _setup.ParticleCount;
        var x = new double[count];
        var y = new double[count];
        var z = new double[count];
        for (var i = 0; i < count; i++)
        {
            x[i] = row[1 + (6 * i)];
            y[i] = row[2 + (6 * i)];
            z[i] = row[3 + (6 * i)];
        }

        return new Snapshot(row[0], x, y, z);
    }

    private sealed record Snapshot(double Time, double[] X, double[] Y, double[] Z)
    {
        public Vector3d At(int i) => new(X[i], Y[i], Z[i]);
    }
}
