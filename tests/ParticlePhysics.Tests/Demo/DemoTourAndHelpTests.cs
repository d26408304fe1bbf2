using System;
using System.Linq;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Tests.Demo;

/// <summary>The no-argument tour, the table format, and the help.</summary>
public class DemoTourAndHelpTests
{
    [Fact]
    public void Without_arguments_every_scenario_runs_under_every_integrator_that_applies_in_one_table()
    {
        var result = DemoProcess.Run();

        Assert.Equal(0, result.ExitCode);
        Assert.Equal("", result.Error);
        var lines = result.OutputLines;
        var header = lines.Single(l => l.StartsWith("scenario ", StringComparison.Ordinal));
        foreach (var column in new[] { "integrator", "dt (s)", "final state", "error" })
        {
            Assert.Contains(column, header, StringComparison.Ordinal);
        }

        foreach (var scenario in new[] { "free-fall", "mass-spring-damper", "two-mass-chain", "cloth" })
        {
            Assert.Equal(IntegratorCatalog.Names.Count, lines.Count(l => l.StartsWith(scenario + " ", StringComparison.Ordinal)));
        }

        var scalar = IntegratorCatalog.Names.Count(n => !IntegratorCatalog.NeedsSecondOrderSystem(n));
        Assert.Equal(scalar, lines.Count(l => l.StartsWith("scalar-ode ", StringComparison.Ordinal)));
        var rk4 = lines.Single(l => l.StartsWith("free-fall ", StringComparison.Ordinal) && l.Contains(" rk4 ", StringComparison.Ordinal));
        Assert.Matches(@"\d\.\d\dE-1\d$", rk4); // an error near 1e-12
    }

    [Fact]
    public void The_table_format_has_aligned_columns_and_a_summary_line_with_the_error()
    {
        var result = DemoProcess.Run("free-fall", "--duration", "1", "--every", "10");

        var lines = result.OutputLines;
        Assert.StartsWith("free-fall: rk4, dt = 0.01 s", lines[0], StringComparison.Ordinal);
        var body = lines.Skip(1).Take(lines.Length - 2).ToArray();
        Assert.Equal(12, body.Length); // header + 11 rows
        Assert.Single(body.Select(l => l.Length).Distinct());
        Assert.Matches(@"^final state at t = 1 s: y0 = 296\.39\d*, vy0 = -6\.20\d*; error against the exact solution .*: \d\.\d\dE-\d\d$", lines[^1]);
    }

    [Theory]
    [InlineData("--help")]
    [InlineData("free-fall", "--help")]
    [InlineData("cloth", "-h")]
    [InlineData("convergence", "mass-spring-damper", "--help")]
    public void Help_lists_the_options_with_their_defaults_and_units(params string[] args)
    {
        var result = DemoProcess.Run(args);

        Assert.Equal(0, result.ExitCode);
        Assert.Contains("Usage:", result.Output, StringComparison.Ordinal);
        if (args.Length > 1)
        {
            Assert.Contains("--dt <s>", result.Output, StringComparison.Ordinal);
            Assert.Contains("[default: ", result.Output, StringComparison.Ordinal);
            Assert.Contains("--integrator", result.Output, StringComparison.Ordinal);
        }
        else
        {
            Assert.Contains("convergence", result.Output, StringComparison.Ordinal);
        }
    }

    [Fact]
    public void Free_fall_help_shows_the_contract_defaults()
    {
        var help = DemoProcess.Run("free-fall", "--help").Output;

        Assert.Matches(@"--mass <kg>\s+.*\[default: 0\.01\]", help);
        Assert.Matches(@"--height <m>\s+.*\[default: 300\]", help);
        Assert.Matches(@"--dt <s>\s+.*\[default: 0\.01\]", help);
        Assert.Matches(@"--duration <s>\s+.*\[default: 10\]", help);
    }
}
