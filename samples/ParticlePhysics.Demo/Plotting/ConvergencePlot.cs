using System.Linq;
using ParticlePhysics.Demo.Output;
using ParticlePhysics.Demo.Scenarios;

namespace ParticlePhysics.Demo.Plotting;

/// <summary>The error at the end time against dt, log-log: one line per integrator, whose slope is its order.</summary>
internal static class ConvergencePlot
{
    public static string ToSvg(ConvergenceStudy study)
    {
        var chart = new LineChart(
            $"convergence on {study.Setup.Name}: error at t = {Numbers.Brief(study.EndTime)} s",
            "dt (s)",
            "max abs error",
            logX: true,
            logY: true);
        var groups = study.Rows.GroupBy(r => r.Integrator).ToArray();
        for (var g = 0; g < groups.Length; g++)
        {
            var rows = groups[g].ToArray();
            var last = rows.LastOrDefault(r => r.Order is not null)?.Order;
            var label = last is { } o ? $"{groups[g].Key} (order {o.ToString("0.0", System.Globalization.CultureInfo.InvariantCulture)})" : groups[g].Key;
            chart.Add(label, rows.Select(r => r.Plan.Dt).ToArray(), rows.Select(r => r.Error).ToArray(), LineChart.Palette[g % LineChart.Palette.Length], markers: true);
        }

        return chart.ToSvg();
    }
}
