using System;
using System.Globalization;
using System.Linq;
using ParticlePhysics.Demo.Output;
using ParticlePhysics.Demo.Scenarios;

namespace ParticlePhysics.Demo.Plotting;

/// <summary>
/// The error at the end time against dt, log-log: one line per integrator, whose slope is its order, each with its
/// own marker and dash pattern (explicit and implicit Euler nearly coincide, and both stay visible), over dotted
/// reference lines of slope 1, 2 and 4.
/// </summary>
internal static class ConvergencePlot
{
    /// <summary>The slopes of the reference lines: the orders of the Euler methods, velocity Verlet and RK4.</summary>
    public static readonly int[] ReferenceSlopes = { 1, 2, 4 };

    public static string ToSvg(ConvergenceStudy study)
    {
        var chart = new LineChart(
            $"convergence on {study.Setup.Name}: error at t = {Numbers.Brief(study.EndTime)} s against dt",
            "dt (s)",
            "max abs error",
            logX: true,
            logY: true);
        var usable = study.Rows.Where(r => double.IsFinite(r.Error) && r.Error > 0).ToArray();
        foreach (var slope in ReferenceSlopes)
        {
            // Through the finest point of the lowest integrator of that order, a little below it, so the line runs
            // beside its data; through the middle of the data when no integrator has that order.
            var own = usable.Where(r => r.ExpectedOrder == slope).OrderBy(r => r.Error).FirstOrDefault();
            if (own is not null)
            {
                chart.AddReferenceSlope(slope, own.Plan.Dt, own.Error / 3, $"slope {slope}");
            }
            else if (usable.Length > 0)
            {
                var x = Math.Sqrt(usable.Min(r => r.Plan.Dt) * usable.Max(r => r.Plan.Dt));
                var y = Math.Sqrt(usable.Min(r => r.Error) * usable.Max(r => r.Error));
                chart.AddReferenceSlope(slope, x, y, $"slope {slope}");
            }
        }

        var groups = study.Rows.GroupBy(r => r.Integrator).ToArray();
        for (var g = 0; g < groups.Length; g++)
        {
            var rows = groups[g].ToArray();
            var last = rows.LastOrDefault(r => r.Order is not null)?.Order;
            var label = last is { } o ? $"{groups[g].Key} (order {o.ToString("0.0", CultureInfo.InvariantCulture)})" : groups[g].Key;
            var dash = LineChart.Dashes[g % LineChart.Dashes.Length];
            var style = new SeriesStyle(LineChart.Palette[g % LineChart.Palette.Length], dash is null ? 2.6 : 2, dash, LineChart.Markers[g % LineChart.Markers.Length]);
            chart.Add(label, rows.Select(r => r.Plan.Dt).ToArray(), rows.Select(r => r.Error).ToArray(), style);
        }

        return chart.ToSvg();
    }
}
