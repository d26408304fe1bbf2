using System.Collections.Generic;
using System.Globalization;
using System.Security;
using System.Text;

namespace ParticlePhysics.Demo.Plotting;

/// <summary>
/// A minimal SVG writer. Hand-written because OxyPlot.Core (the usual .NET choice) is not on our package mirror and
/// the charts need only lines, polylines, markers and text.
/// </summary>
internal sealed class SvgCanvas
{
    private readonly StringBuilder _body = new();
    private readonly double _width;
    private readonly double _height;

    public SvgCanvas(double width, double height)
    {
        _width = width;
        _height = height;
    }

    public void Rect(double x, double y, double width, double height, string fill, string stroke = "none") =>
        _body.Append(CultureInfo.InvariantCulture, $"<rect x=\"{F(x)}\" y=\"{F(y)}\" width=\"{F(width)}\" height=\"{F(height)}\" fill=\"{fill}\" stroke=\"{stroke}\"/>\n");

    public void Line(double x1, double y1, double x2, double y2, string stroke, double width = 1, string? dash = null) =>
        _body.Append(CultureInfo.InvariantCulture, $"<line x1=\"{F(x1)}\" y1=\"{F(y1)}\" x2=\"{F(x2)}\" y2=\"{F(y2)}\" stroke=\"{stroke}\" stroke-width=\"{F(width)}\"{Dash(dash)}/>\n");

    public void Polyline(IEnumerable<(double X, double Y)> points, string stroke, double width = 1.5, string? dash = null)
    {
        _body.Append("<polyline fill=\"none\" stroke=\"").Append(stroke).Append(CultureInfo.InvariantCulture, $"\" stroke-width=\"{F(width)}\"{Dash(dash)} points=\"");
        var first = true;
        foreach (var (x, y) in points)
        {
            _body.Append(first ? string.Empty : " ").Append(F(x)).Append(',').Append(F(y));
            first = false;
        }

        _body.Append("\"/>\n");
    }

    public void Circle(double x, double y, double radius, string fill) =>
        _body.Append(CultureInfo.InvariantCulture, $"<circle cx=\"{F(x)}\" cy=\"{F(y)}\" r=\"{F(radius)}\" fill=\"{fill}\"/>\n");

    /// <summary>Text; <paramref name="anchor"/> is start, middle or end; <paramref name="rotate"/> turns it about its anchor.</summary>
    public void Text(double x, double y, string text, string anchor = "start", double size = 12, double rotate = 0, string weight = "normal")
    {
        var transform = rotate == 0 ? string.Empty : string.Create(CultureInfo.InvariantCulture, $" transform=\"rotate({F(rotate)} {F(x)} {F(y)})\"");
        _body.Append(CultureInfo.InvariantCulture, $"<text x=\"{F(x)}\" y=\"{F(y)}\" font-size=\"{F(size)}\" text-anchor=\"{anchor}\" font-weight=\"{weight}\"{transform}>{SecurityElement.Escape(text)}</text>\n");
    }

    public override string ToString() =>
        string.Create(CultureInfo.InvariantCulture, $"<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{F(_width)}\" height=\"{F(_height)}\" viewBox=\"0 0 {F(_width)} {F(_height)}\" font-family=\"sans-serif\">\n")
        + _body + "</svg>\n";

    private static string F(double value) => value.ToString("0.##", CultureInfo.InvariantCulture);

    private static string Dash(string? dash) => dash is null ? string.Empty : $" stroke-dasharray=\"{dash}\"";
}
