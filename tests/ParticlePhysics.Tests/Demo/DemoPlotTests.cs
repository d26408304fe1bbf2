using System;
using System.Globalization;
using System.IO;
using System.Linq;
using System.Xml.Linq;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Tests.Demo;

/// <summary>
/// <c>--plot</c> writes an SVG document that parses as XML and holds the curves it announces: every curve with its
/// own marker or dash pattern, the exact curve over the computed one and thinner, reference slopes on convergence
/// charts, axes and pins on the cloth's panels and a perspective view, and no text past the edges.
/// </summary>
public sealed class DemoPlotTests : IDisposable
{
    private static readonly XNamespace _svg = "http://www.w3.org/2000/svg";
    private readonly string _folder = Directory.CreateTempSubdirectory("pp-demo-plot-").FullName;

    public void Dispose() => Directory.Delete(_folder, recursive: true);

    [Fact]
    public void A_trajectory_plot_has_the_computed_and_the_exact_curve()
    {
        var path = Path.Combine(_folder, "free-fall.svg");

        var result = DemoProcess.Run("free-fall", "--plot", path, "--format", "csv");

        Assert.Equal(0, result.ExitCode);
        var document = XDocument.Load(path);
        Assert.Equal(_svg + "svg", document.Root!.Name);
        var curves = document.Descendants(_svg + "polyline").ToArray();
        Assert.Equal(2, curves.Length);
        var texts = document.Descendants(_svg + "text").Select(t => t.Value).ToArray();
        Assert.Contains("y0 (rk4)", texts);
        Assert.Contains("y0 exact", texts);
        Assert.Contains("t (s)", texts);

        // The exact curve comes second (on top), thinner and dashed; the computed one carries markers.
        Assert.True(Width(curves[1]) < Width(curves[0]));
        Assert.NotNull(curves[1].Attribute("stroke-dasharray"));
        Assert.True(document.Descendants(_svg + "circle").Count() >= 10);
        AssertNothingClipped(document);
    }

    [Fact]
    public void Each_curve_of_a_chain_has_its_own_marker_and_the_exact_curves_lie_on_top()
    {
        var path = Path.Combine(_folder, "chain.svg");

        Assert.Equal(0, DemoProcess.Run("two-mass-chain", "--plot", path, "--format", "csv").ExitCode);

        var document = XDocument.Load(path);
        var curves = document.Descendants(_svg + "polyline").ToArray();
        Assert.Equal(4, curves.Length);
        Assert.All(curves.Skip(2), exact => Assert.True(Width(exact) < Width(curves[0])));
        Assert.True(document.Descendants(_svg + "circle").Any());   // y0's markers
        Assert.True(document.Descendants(_svg + "polygon").Any());  // y1's squares
        AssertNothingClipped(document);
    }

    [Fact]
    public void A_convergence_plot_is_log_log_with_one_line_per_integrator()
    {
        var path = Path.Combine(_folder, "convergence.svg");

        var result = DemoProcess.Run("convergence", "mass-spring-damper", "--plot", path);

        Assert.Equal(0, result.ExitCode);
        var document = XDocument.Load(path);
        var fixedStep = IntegratorCatalog.Names.Count(n => IntegratorCatalog.Create(n) is not DormandPrince45);
        Assert.Equal(fixedStep, document.Descendants(_svg + "polyline").Count());
        var texts = document.Descendants(_svg + "text").Select(t => t.Value).ToArray();
        Assert.Contains(texts, t => t.StartsWith("rk4 (order 4.0", StringComparison.Ordinal));
        Assert.Contains(texts, t => t.StartsWith("1e-", StringComparison.Ordinal)); // decade ticks
        Assert.Equal(new[] { "slope 1", "slope 2", "slope 4" }, texts.Where(t => t.StartsWith("slope ", StringComparison.Ordinal)).Order());

        // Explicit and implicit Euler nearly coincide: each integrator has a dash pattern of its own (or none).
        var dashes = document.Descendants(_svg + "polyline").Select(p => (string?)p.Attribute("stroke-dasharray") ?? "solid").ToArray();
        Assert.Equal(dashes.Length, dashes.Distinct().Count());
        AssertNothingClipped(document);
    }

    [Fact]
    public void A_cloth_plot_shows_four_snapshots_of_the_mesh()
    {
        var path = Path.Combine(_folder, "cloth.svg");

        var result = DemoProcess.Run("cloth", "--plot", path, "--duration", "0.6", "--format", "csv");

        Assert.Equal(0, result.ExitCode);
        var document = XDocument.Load(path);
        var texts = document.Descendants(_svg + "text").Select(t => t.Value).ToArray();
        var times = new[] { "t = 0 s", "t = 0.2 s", "t = 0.4 s", "t = 0.6 s" };
        Assert.Equal(times.SelectMany(t => new[] { t, t }), texts.Where(t => t.StartsWith("t = ", StringComparison.Ordinal))); // front and perspective
        Assert.Equal(4 * 2 * 11, document.Descendants(_svg + "polyline").Count()); // 11 rows and 11 columns per snapshot
        Assert.Equal(4, texts.Count(t => t == "x (m)"));
        Assert.Equal(4, texts.Count(t => t == "y (m)"));
        Assert.Equal(4 * 100, document.Descendants(_svg + "polygon").Count()); // the perspective views' 10 x 10 cells
        var pins = document.Descendants(_svg + "rect").Count(r => (string?)r.Attribute("fill") == "#C62828");
        Assert.Equal(8 * 2, pins); // two pinned corners in each of the eight panels
        AssertNothingClipped(document);
    }

    [Fact]
    public void A_drape_plot_draws_the_sphere_in_every_panel()
    {
        var path = Path.Combine(_folder, "drape.svg");

        var result = DemoProcess.Run("drape", "--plot", path, "--duration", "0.3", "--format", "csv");

        Assert.Equal(0, result.ExitCode);
        var document = XDocument.Load(path);
        Assert.StartsWith("drape: 11 x 11 particles", document.Descendants(_svg + "text").First().Value, StringComparison.Ordinal);

        // Front: the sphere's outline (a closed grey polyline) in each of the four panels, besides the 22 grid lines;
        // perspective: a grey disc in each.
        var grey = document.Descendants(_svg + "polyline").Count(l => (string?)l.Attribute("stroke") == "#999999");
        Assert.Equal(4, grey);
        Assert.Equal(4, document.Descendants(_svg + "circle").Count(c => (string?)c.Attribute("fill") == "rgb(150,158,168)"));
        Assert.Equal(0, document.Descendants(_svg + "rect").Count(r => (string?)r.Attribute("fill") == "#C62828")); // no pins
        AssertNothingClipped(document);
    }

    [Fact]
    public void Convergence_on_the_pendulum_has_its_reference_slopes_clear_of_the_markers()
    {
        var path = Path.Combine(_folder, "pendulum.svg");

        var result = DemoProcess.Run("convergence", "pendulum", "--plot", path);

        Assert.Equal(0, result.ExitCode);
        var document = XDocument.Load(path);
        var labels = document.Descendants(_svg + "text").Where(t => t.Value.StartsWith("slope ", StringComparison.Ordinal)).ToArray();
        Assert.Equal(new[] { "slope 1", "slope 2", "slope 4" }, labels.Select(t => t.Value).Order());

        // No marker (their polylines' points) lies under a label's box (0.6 em a character, 10 px high).
        var points = document.Descendants(_svg + "polyline").Where(p => p.Attribute("stroke-dasharray")?.Value != "1.5 3")
            .SelectMany(p => ((string)p.Attribute("points")!).Split(' ')).Select(Point).ToArray();
        foreach (var label in labels)
        {
            double At(string name) => double.Parse((string)label.Attribute(name)!, CultureInfo.InvariantCulture);
            var (x, y, width) = (At("x"), At("y"), label.Value.Length * 10 * 0.6);
            Assert.DoesNotContain(points, p => p.X > x - 4 && p.X < x + width + 4 && p.Y > y - 14 && p.Y < y + 4);
        }

        AssertNothingClipped(document);
    }

    [Fact]
    public void A_curve_on_the_frame_is_not_cut_by_it()
    {
        var path = Path.Combine(_folder, "pendulum.svg");

        var result = DemoProcess.Run("pendulum", "--plot", path, "--format", "csv");

        // The bob starts at y = 0, the top of the axis: the series' clip reaches past the frame, the references' not.
        Assert.Equal(0, result.ExitCode);
        var document = XDocument.Load(path);
        var frame = document.Descendants(_svg + "rect").Single(r => (string?)r.Attribute("stroke") == "#333");
        var clip = document.Descendants(_svg + "clipPath").Last().Element(_svg + "rect")!;
        double Of(XElement e, string name) => double.Parse((string)e.Attribute(name)!, CultureInfo.InvariantCulture);
        Assert.True(Of(clip, "y") <= Of(frame, "y") - 6, "the clip leaves room for a marker on the top edge");
        Assert.True(Of(clip, "x") <= Of(frame, "x") - 6, "and on the left edge");
    }

    [Fact]
    public void A_diverged_run_still_writes_a_plot_of_what_it_computed()
    {
        var path = Path.Combine(_folder, "diverged.svg");

        var result = DemoProcess.Run("cloth", "--dt", "0.0166667", "--plot", path, "--format", "csv");

        Assert.Equal(3, result.ExitCode);
        var document = XDocument.Load(path);
        Assert.Contains("diverged", document.Descendants(_svg + "text").First().Value, StringComparison.Ordinal);
        AssertNothingClipped(document);
    }

    private static (double X, double Y) Point(string pair)
    {
        var parts = pair.Split(',');
        return (double.Parse(parts[0], CultureInfo.InvariantCulture), double.Parse(parts[1], CultureInfo.InvariantCulture));
    }

    private static double Width(XElement element) => double.Parse((string)element.Attribute("stroke-width")!, CultureInfo.InvariantCulture);

    /// <summary>Every text, at the width the charts are laid out with (0.6 em a character, 0.66 in bold), lies inside the canvas.</summary>
    private static void AssertNothingClipped(XDocument document)
    {
        var width = double.Parse((string)document.Root!.Attribute("width")!, CultureInfo.InvariantCulture);
        var height = double.Parse((string)document.Root!.Attribute("height")!, CultureInfo.InvariantCulture);
        foreach (var text in document.Descendants(_svg + "text").Where(t => t.Attribute("transform") is null))
        {
            double At(string name) => double.Parse((string)text.Attribute(name)!, CultureInfo.InvariantCulture);
            var size = At("font-size");
            var extent = text.Value.Length * size * ((string?)text.Attribute("font-weight") == "bold" ? 0.66 : 0.6);
            var x = At("x");
            var (from, to) = (string?)text.Attribute("text-anchor") switch
            {
                "middle" => (x - (extent / 2), x + (extent / 2)),
                "end" => (x - extent, x),
                _ => (x, x + extent),
            };
            Assert.True(from >= 0 && to <= width, $"'{text.Value}' spans x = {from:0} to {to:0}, past the width {width}");
            Assert.True(At("y") - size >= 0 && At("y") <= height, $"'{text.Value}' at y = {At("y")} is outside the height {height}");
        }
    }
}
