using System;
using System.Collections.Generic;
using System.Linq;

namespace ParticlePhysics.Demo.Plotting;

/// <summary>
/// An x-y chart of a few series (lines, dashed lines, markers) with ticks, axis labels, a title and a legend;
/// either axis may be logarithmic.
/// </summary>
internal sealed class LineChart
{
    /// <summary>A colour-blind-safe palette (Okabe and Ito).</summary>
    public static readonly string[] Palette = { "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000" };

    private const double Width = 820, Height = 460, Left = 80, Right = 250, Top = 40, Bottom = 60;
    private readonly List<Series> _series = new();

    public LineChart(string title, string xLabel, string yLabel, bool logX = false, bool logY = false)
    {
        Title = title;
        XLabel = xLabel;
        YLabel = yLabel;
        LogX = logX;
        LogY = logY;
    }

    public string Title { get; }

    public string XLabel { get; }

    public string YLabel { get; }

    public bool LogX { get; }

    public bool LogY { get; }

    /// <summary>Adds a series; <paramref name="dashed"/> draws a dashed line, <paramref name="markers"/> dots at the points.</summary>
    public void Add(string label, IReadOnlyList<double> x, IReadOnlyList<double> y, string color, bool dashed = false, bool markers = false) =>
        _series.Add(new Series(label, x, y, color, dashed, markers));

    public string ToSvg()
    {
        var xAxis = Axis.Covering(_series.SelectMany(s => s.X), LogX);
        var yAxis = Axis.Covering(_series.SelectMany(s => s.Y), LogY);
        double plotWidth = Width - Left - Right, plotHeight = Height - Top - Bottom;
        double Px(double x) => Left + (xAxis.Fraction(x) * plotWidth);
        double Py(double y) => Top + plotHeight - (yAxis.Fraction(y) * plotHeight);

        var svg = new SvgCanvas(Width, Height);
        svg.Rect(0, 0, Width, Height, "white");
        svg.Text(Left + (plotWidth / 2), 24, Title, "middle", 15, weight: "bold");
        foreach (var tick in xAxis.Ticks)
        {
            svg.Line(Px(tick), Top, Px(tick), Top + plotHeight, "#e4e4e4");
            svg.Line(Px(tick), Top + plotHeight, Px(tick), Top + plotHeight + 5, "#333");
            svg.Text(Px(tick), Top + plotHeight + 19, xAxis.Label(tick), "middle", 11);
        }

        foreach (var tick in yAxis.Ticks)
        {
            svg.Line(Left, Py(tick), Left + plotWidth, Py(tick), "#e4e4e4");
            svg.Line(Left - 5, Py(tick), Left, Py(tick), "#333");
            svg.Text(Left - 8, Py(tick) + 4, yAxis.Label(tick), "end", 11);
        }

        svg.Rect(Left, Top, plotWidth, plotHeight, "none", "#333");
        svg.Text(Left + (plotWidth / 2), Height - 16, XLabel, "middle", 13);
        svg.Text(20, Top + (plotHeight / 2), YLabel, "middle", 13, rotate: -90);

        foreach (var s in _series)
        {
            var points = Enumerable.Range(0, Math.Min(s.X.Count, s.Y.Count))
                .Where(i => Usable(s.X[i], LogX) && Usable(s.Y[i], LogY))
                .Select(i => (Px(s.X[i]), Py(s.Y[i])))
                .ToArray();
            svg.Polyline(points, s.Color, s.Dashed ? 1.5 : 2, s.Dashed ? "6 4" : null);
            if (s.Markers)
            {
                foreach (var (x, y) in points)
                {
                    svg.Circle(x, y, 3.5, s.Color);
                }
            }
        }

        var legendX = Left + plotWidth + 16;
        for (var i = 0; i < _series.Count; i++)
        {
            var s = _series[i];
            var y = Top + 10 + (i * 20);
            svg.Line(legendX, y, legendX + 26, y, s.Color, 2, s.Dashed ? "6 4" : null);
            if (s.Markers)
            {
                svg.Circle(legendX + 13, y, 3.5, s.Color);
            }

            svg.Text(legendX + 32, y + 4, s.Label, "start", 11);
        }

        return svg.ToString();
    }

    private static bool Usable(double value, bool logarithmic) => double.IsFinite(value) && (!logarithmic || value > 0);

    private sealed record Series(string Label, IReadOnlyList<double> X, IReadOnlyList<double> Y, string Color, bool Dashed, bool Markers);
}
