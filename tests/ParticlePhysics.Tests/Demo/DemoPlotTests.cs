using System;
using System.IO;
using System.Linq;
using System.Xml.Linq;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Tests.Demo;

/// <summary><c>--plot</c> writes an SVG document that parses as XML and holds the curves it announces.</summary>
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
        Assert.Equal(2, document.Descendants(_svg + "polyline").Count());
        var texts = document.Descendants(_svg + "text").Select(t => t.Value).ToArray();
        Assert.Contains("y0 (rk4)", texts);
        Assert.Contains("y0 exact", texts);
        Assert.Contains("t (s)", texts);
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
    }

    [Fact]
    public void A_cloth_plot_shows_four_snapshots_of_the_mesh()
    {
        var path = Path.Combine(_folder, "cloth.svg");

        var result = DemoProcess.Run("cloth", "--plot", path, "--duration", "0.6", "--format", "csv");

        Assert.Equal(0, result.ExitCode);
        var document = XDocument.Load(path);
        var texts = document.Descendants(_svg + "text").Select(t => t.Value).ToArray();
        Assert.Equal(new[] { "t = 0 s", "t = 0.2 s", "t = 0.4 s", "t = 0.6 s" }, texts.Where(t => t.StartsWith("t = ", StringComparison.Ordinal)));
        Assert.Equal(4 * 2 * 11, document.Descendants(_svg + "polyline").Count()); // 11 rows and 11 columns per snapshot
    }

    [Fact]
    public void A_diverged_run_still_writes_a_plot_of_what_it_computed()
    {
        var path = Path.Combine(_folder, "diverged.svg");

        var result = DemoProcess.Run("cloth", "--dt", "0.0166667", "--plot", path, "--format", "csv");

        Assert.Equal(3, result.ExitCode);
        Assert.Contains("diverged", XDocument.Load(path).Descendants(_svg + "text").First().Value, StringComparison.Ordinal);
    }
}
