using System;
using System.Collections.Generic;
using System.Globalization;
using System.Security;
using System.Text;

namespace ParticlePhysics.Demo.Plotting;

/// <summary>
/// A minimal SVG writer: rectangles, lines, polylines, polygons, markers, text and clipping regions.
/// </summary>
/// <remarks>
/// Hand-written rather than OxyPlot.Core's SvgExporter (which does restore from the package mirror): that exporter
/// measures text without a font engine, and its charts, rendered and looked at, come out with the legend clipped at
/// the right edge and the axis titles over the tick labels; a real text measurer means a rendering backend with
/// native libraries (OxyPlot.SkiaSharp, and ScottPlot 5, which is built on SkiaSharp). The cloth panels (projections,
/// pins, a perspective view) would be drawn by hand on either library. This writer estimates text widths with
/// <see cref="TextWidth"/> and sizes every chart to fit them, so nothing is clipped, with no dependency.
/// </remarks>
internal sealed class SvgCanvas
{
    private readonly StringBuilder _defs = new();
    private readonly StringBuilder _body = new();
    private readonly double _width;
    private readonly double _height;
    private int _clips;

    public SvgCanvas(double width, double height)
    {
        _width = width;
        _height = height;
    }

    /// <summary>
    /// A generous estimate of the width of <paramref name="text"/> in the sans-serif fonts browsers pick (about 0.6 em
    /// per character, 0.66 em in bold), so that a layout sized with it never clips.
    /// </summary>
    public static double TextWidth(string text, double size, bool bold = false) => text.Length * size * (bold ? 0.66 : 0.6);

    public void Rect(double x, double y, double width, double height, string fill, string stroke = "none") =>
        _body.Append(CultureInfo.InvariantCulture, $"<rect x=\"{F(x)}\" y=\"{F(y)}\" width=\"{F(width)}\" height=\"{F(height)}\" fill=\"{fill}\" stroke=\"{stroke}\"/>\n");

    public void Line(double x1, double y1, double x2, double y2, string stroke, double width = 1, string? dash = null) =>
        _body.Append(CultureInfo.InvariantCulture, $"<line x1=\"{F(x1)}\" y1=\"{F(y1)}\" x2=\"{F(x2)}\" y2=\"{F(y2)}\" stroke=\"{stroke}\" stroke-width=\"{F(width)}\"{Dash(dash)}/>\n");

    public void Polyline(IEnumerable<(double X, double Y)> points, string stroke, double width = 1.5, string? dash = null)
    {
        _body.Append("<polyline fill=\"none\" stroke=\"").Append(stroke).Append(CultureInfo.InvariantCulture, $"\" stroke-width=\"{F(width)}\" stroke-linejoin=\"round\"{Dash(dash)} points=\"");
        Points(points);
        _body.Append("\"/>\n");
    }

    public void Polygon(IEnumerable<(double X, double Y)> points, string fill, string stroke = "none", double width = 1)
    {
        _body.Append("<polygon fill=\"").Append(fill).Append("\" stroke=\"").Append(stroke)
            .Append(CultureInfo.InvariantCulture, $"\" stroke-width=\"{F(width)}\" stroke-linejoin=\"round\" points=\"");
        Points(points);
        _body.Append("\"/>\n");
    }

    public void Circle(double x, double y, double radius, string fill, string stroke = "none", double width = 1) =>
        _body.Append(CultureInfo.InvariantCulture, $"<circle cx=\"{F(x)}\" cy=\"{F(y)}\" r=\"{F(radius)}\" fill=\"{fill}\" stroke=\"{stroke}\" stroke-width=\"{F(width)}\"/>\n");

    /// <summary>A marker of <paramref name="shape"/> centred on (x, y), outlined in <paramref name="color"/> and hollow, so that markers on top of each other all show.</summary>
    public void Marker(MarkerShape shape, double x, double y, string color, double size = 4.5)
    {
        const string fill = "white";
        var s = size;
        switch (shape)
        {
            case MarkerShape.Circle:
                Circle(x, y, s, fill, color, 1.6);
                break;
            case MarkerShape.Square:
                Polygon(new[] { (x - (0.85 * s), y - (0.85 * s)), (x + (0.85 * s), y - (0.85 * s)), (x + (0.85 * s), y + (0.85 * s)), (x - (0.85 * s), y + (0.85 * s)) }, fill, color, 1.6);
                break;
            case MarkerShape.Triangle:
                Polygon(new[] { (x, y - (1.15 * s)), (x + s, y + (0.75 * s)), (x - s, y + (0.75 * s)) }, fill, color, 1.6);
                break;
            case MarkerShape.InvertedTriangle:
                Polygon(new[] { (x, y + (1.15 * s)), (x + s, y - (0.75 * s)), (x - s, y - (0.75 * s)) }, fill, color, 1.6);
                break;
            case MarkerShape.Diamond:
                Polygon(new[] { (x, y - (1.25 * s)), (x + s, y), (x, y + (1.25 * s)), (x - s, y) }, fill, color, 1.6);
                break;
            case MarkerShape.Cross:
                Line(x - s, y - s, x + s, y + s, color, 1.8);
                Line(x - s, y + s, x + s, y - s, color, 1.8);
                break;
            default:
                break;
        }
    }

    /// <summary>Text; <paramref name="anchor"/> is start, middle or end; <paramref name="rotate"/> turns it about its anchor.</summary>
    public void Text(double x, double y, string text, string anchor = "start", double size = 12, double rotate = 0, string weight = "normal", string fill = "#222")
    {
        var transform = rotate == 0 ? string.Empty : string.Create(CultureInfo.InvariantCulture, $" transform=\"rotate({F(rotate)} {F(x)} {F(y)})\"");
        _body.Append(CultureInfo.InvariantCulture, $"<text x=\"{F(x)}\" y=\"{F(y)}\" font-size=\"{F(size)}\" text-anchor=\"{anchor}\" font-weight=\"{weight}\" fill=\"{fill}\"{transform}>{SecurityElement.Escape(text)}</text>\n");
    }

    /// <summary>Starts a group whose drawing is clipped to a rectangle (a chart's plot area); end it with <see cref="EndGroup"/>.</summary>
    public void BeginClip(double x, double y, double width, double height)
    {
        var id = string.Create(CultureInfo.InvariantCulture, $"clip{++_clips}");
        _defs.Append(CultureInfo.InvariantCulture, $"<clipPath id=\"{id}\"><rect x=\"{F(x)}\" y=\"{F(y)}\" width=\"{F(width)}\" height=\"{F(height)}\"/></clipPath>\n");
        _body.Append(CultureInfo.InvariantCulture, $"<g clip-path=\"url(#{id})\">\n");
    }

    public void EndGroup() => _body.Append("</g>\n");

    public override string ToString() =>
        string.Create(CultureInfo.InvariantCulture, $"<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{F(_width)}\" height=\"{F(_height)}\" viewBox=\"0 0 {F(_width)} {F(_height)}\" font-family=\"sans-serif\">\n")
        + (_defs.Length == 0 ? string.Empty : "<defs>\n" + _defs + "</defs>\n")
        + _body + "</svg>\n";

    private void Points(IEnumerable<(double X, double Y)> points)
    {
        var first = true;
        foreach (var (x, y) in points)
        {
            _body.Append(first ? string.Empty : " ").Append(F(x)).Append(',').Append(F(y));
            first = false;
        }
    }

    private static string F(double value) => Math.Round(value, 2).ToString("0.##", CultureInfo.InvariantCulture);

    private static string Dash(string? dash) => dash is null ? string.Empty : $" stroke-dasharray=\"{dash}\"";
}

/// <summary>The marker shapes of a chart's series.</summary>
internal enum MarkerShape
{
    /// <summary>No marker.</summary>
    None,

    /// <summary>A circle.</summary>
    Circle,

    /// <summary>A square.</summary>
    Square,

    /// <summary>A triangle pointing up.</summary>
    Triangle,

    /// <summary>A diamond.</summary>
    Diamond,

    /// <summary>A triangle pointing down.</summary>
    InvertedTriangle,

    /// <summary>An x.</summary>
    Cross,
}
