using System;
using System.Collections.Generic;
using System.Linq;

namespace ParticlePhysics.Demo.Plotting;

/// <summary>How a series is drawn: colour, width, dash pattern and marker (every <see cref="MarkerEvery"/>-th point, 1 for all).</summary>
internal sealed record SeriesStyle(string Color, double Width = 2, string? Dash = null, MarkerShape Marker = MarkerShape.None, int MarkerEvery = 1, int MarkerPhase = 0);

/// <summary>
/// An x-y chart of a few series with ticks, axis labels, a title and a legend; either axis may be logarithmic.
/// Series are drawn in the order they were added, so the last one lies on top. Reference lines of a given slope
/// on log-log axes (error against dt: slope p for order p) are drawn thin, grey and dotted under the series.
/// The canvas grows to fit the title and the legend, so that no text is clipped. The reference lines are clipped to
/// the plot area; the series to a few pixels more, so that a curve or a marker on the frame (a height that starts at
/// a tick) shows whole.
/// </summary>
internal sealed class LineChart
{
    /// <summary>A colour-blind-safe palette (Okabe and Ito).</summary>
    public static readonly string[] Palette = { "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000" };

    /// <summary>Marker shapes in the order series take them.</summary>
    public static readonly MarkerShape[] Markers =
        { MarkerShape.Circle, MarkerShape.Square, MarkerShape.Triangle, MarkerShape.Diamond, MarkerShape.InvertedTriangle, MarkerShape.Cross };

    /// <summary>Dash patterns in the order series take them (solid first).</summary>
    public static readonly string?[] Dashes = { null, "9 4", "3 3", "12 3 3 3", "6 3 1 3", "2 5", "14 4 2 4 2 4" };

    private const double Overhang = 8;
    private const double PlotWidth = 560, PlotHeight = 360, Top = 46, Bottom = 58, TitleSize = 15, LabelSize = 11;
    private readonly List<Series> _series = new();
    private readonly List<Reference> _references = new();

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

    /// <summary>Adds a series, drawn over those added before.</summary>
    public void Add(string label, IReadOnlyList<double> x, IReadOnlyList<double> y, SeriesStyle style) =>
        _series.Add(new Series(label, x, y, style));

    /// <summary>A reference line y = c x^<paramref name="slope"/> through (<paramref name="x"/>, <paramref name="y"/>), labelled at its lower end.</summary>
    public void AddReferenceSlope(double slope, double x, double y, string label) => _references.Add(new Reference(slope, x, y, label));

    public string ToSvg()
    {
        var xAxis = Axis.Covering(_series.SelectMany(s => s.X), LogX);
        var yAxis = Axis.Covering(_series.SelectMany(s => s.Y), LogY);
        var left = 24 + LabelSize + 10 + yAxis.Ticks.Max(t => SvgCanvas.TextWidth(yAxis.Label(t), LabelSize));
        var legendWidth = _series.Count == 0 ? 0 : 56 + _series.Max(s => SvgCanvas.TextWidth(s.Label, LabelSize));
        var width = Math.Max(left + PlotWidth + 24 + legendWidth + 12, SvgCanvas.TextWidth(Title, TitleSize, bold: true) + 40);
        var height = Math.Max(Top + PlotHeight + Bottom, Top + 20 + (20 * _series.Count));
        double Px(double x) => left + (xAxis.Fraction(x) * PlotWidth);
        double Py(double y) => Top + PlotHeight - (yAxis.Fraction(y) * PlotHeight);

        var svg = new SvgCanvas(width, height);
        svg.Rect(0, 0, width, height, "white");
        svg.Text(width / 2, 26, Title, "middle", TitleSize, weight: "bold");
        foreach (var tick in xAxis.Ticks)
        {
            svg.Line(Px(tick), Top, Px(tick), Top + PlotHeight, "#e6e6e6");
            svg.Line(Px(tick), Top + PlotHeight, Px(tick), Top + PlotHeight + 5, "#333");
            svg.Text(Px(tick), Top + PlotHeight + 19, xAxis.Label(tick), "middle", LabelSize);
        }

        foreach (var tick in yAxis.Ticks)
        {
            svg.Line(left, Py(tick), left + PlotWidth, Py(tick), "#e6e6e6");
            svg.Line(left - 5, Py(tick), left, Py(tick), "#333");
            svg.Text(left - 8, Py(tick) + 4, yAxis.Label(tick), "end", LabelSize);
        }

        svg.Rect(left, Top, PlotWidth, PlotHeight, "none", "#333");
        svg.Text(left + (PlotWidth / 2), Top + PlotHeight + 44, XLabel, "middle", 13);
        svg.Text(20, Top + (PlotHeight / 2), YLabel, "middle", 13, rotate: -90);

        var drawn = _series.Select(s => Enumerable.Range(0, Math.Min(s.X.Count, s.Y.Count))
            .Where(i => Usable(s.X[i], LogX) && Usable(s.Y[i], LogY))
            .Select(i => (Px(s.X[i]), Py(s.Y[i])))
            .ToArray()).ToArray();
        svg.BeginClip(left, Top, PlotWidth, PlotHeight);
        foreach (var r in _references)
        {
            DrawReference(svg, r, xAxis, yAxis, Px, Py, drawn.SelectMany(p => p).ToArray());
        }

        svg.EndGroup();
        svg.BeginClip(left - Overhang, Top - Overhang, PlotWidth + (2 * Overhang), PlotHeight + (2 * Overhang));
        for (var k = 0; k < _series.Count; k++)
        {
            var s = _series[k];
            var points = drawn[k];
            svg.Polyline(points, s.Style.Color, s.Style.Width, s.Style.Dash);
            if (s.Style.Marker != MarkerShape.None)
            {
                for (var i = s.Style.MarkerPhase % Math.Max(1, s.Style.MarkerEvery); i < points.Length; i += Math.Max(1, s.Style.MarkerEvery))
                {
                    svg.Marker(s.Style.Marker, points[i].Item1, points[i].Item2, s.Style.Color);
                }
            }
        }

        svg.EndGroup();

        var legendX = left + PlotWidth + 24;
        for (var i = 0; i < _series.Count; i++)
        {
            var s = _series[i];
            var y = Top + 10 + (i * 20);
            svg.Line(legendX, y, legendX + 40, y, s.Style.Color, s.Style.Width, s.Style.Dash);
            if (s.Style.Marker != MarkerShape.None)
            {
                svg.Marker(s.Style.Marker, legendX + 20, y, s.Style.Color);
            }

            svg.Text(legendX + 48, y + 4, s.Label, "start", LabelSize);
        }

        return svg.ToString();
    }

    private static void DrawReference(
        SvgCanvas svg, Reference r, Axis xAxis, Axis yAxis, Func<double, double> px, Func<double, double> py, (double X, double Y)[] data)
    {
        // y = y0 (x / x0)^p across the x axis; the clip keeps what leaves the plot area out.
        var (low, high) = (xAxis.Low, xAxis.High);
        double Y(double x) => r.Y * Math.Pow(x / r.X, r.Slope);
        svg.Line(px(low), py(Y(low)), px(high), py(Y(high)), "#777", 1.1, "1.5 3");

        // The label just above the line, where the line is inside the plot, at the place farthest from every data
        // point (so that it covers no marker); the leftmost such place on a tie.
        var width = SvgCanvas.TextWidth(r.Label, 10);
        (double X, double Y)? best = null;
        var bestGap = double.NegativeInfinity;
        for (var k = 0; k <= 40; k++)
        {
            var x = xAxis.At(0.02 + (0.02 * k));
            var f = yAxis.Fraction(Y(x));
            if (!(f > 0.04 && f < 0.92) || xAxis.Fraction(x) > 1 - ((width + 8) / PlotWidth))
            {
                continue;
            }

            var (tx, ty) = (px(x) + 4, py(Y(x)) - 6);
            var gap = data.Length == 0 ? double.PositiveInfinity : data.Min(p => DistanceToBox(p, tx, ty - 9, width, 11));
            if (gap > bestGap + 0.5)
            {
                (best, bestGap) = ((tx, ty), gap);
            }
        }

        if (best is { } at)
        {
            svg.Text(at.X, at.Y, r.Label, "start", 10, fill: "#555");
        }
    }

    private static double DistanceToBox((double X, double Y) p, double left, double top, double width, double height)
    {
        var dx = Math.Max(Math.Max(left - p.X, 0), p.X - (left + width));
        var dy = Math.Max(Math.Max(top - p.Y, 0), p.Y - (top + height));
        return Math.Sqrt((dx * dx) + (dy * dy));
    }

    private static bool Usable(double value, bool logarithmic) => double.IsFinite(value) && (!logarithmic || value > 0);

    private sealed record Series(string Label, IReadOnlyList<double> X, IReadOnlyList<double> Y, SeriesStyle Style);

    private sealed record Reference(double Slope, double X, double Y, string Label);
}
