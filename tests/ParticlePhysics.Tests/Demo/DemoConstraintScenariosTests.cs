using System;
using System.Globalization;
using System.Linq;

namespace ParticlePhysics.Tests.Demo;

/// <summary>The pendulum and the hanging chain from the command line, and xpbd's <c>--substeps</c> on every particle scenario.</summary>
public class DemoConstraintScenariosTests
{
    [Fact]
    public void The_pendulums_summary_gives_the_period_against_4_k_over_w()
    {
        var result = DemoProcess.Run("pendulum");

        Assert.True(result.ExitCode == 0, result.Error);
        var summary = result.OutputLines[^1];
        Assert.Contains("period = 2.36784, period_exact = 2.36784", summary, StringComparison.Ordinal);
        Assert.Contains("error against the exact solution", summary, StringComparison.Ordinal);
        Assert.Matches(@"error against the exact solution[^:]*: \d\.\d\dE-(09|1\d)$", summary);
    }

    [Fact]
    public void The_pendulums_csv_starts_at_the_angle_and_keeps_the_rod()
    {
        var result = DemoProcess.Run("pendulum", "--angle", "120", "--length", "0.5", "--duration", "1", "--format", "csv");

        Assert.True(result.ExitCode == 0, result.Error);
        var (header, rows) = result.Csv();
        Assert.Equal(new[] { "t", "x0", "y0", "z0", "vx0", "vy0", "vz0", "y0_exact", "vy0_exact", "error", "energy", "angle", "angle_exact", "period", "period_exact", "rod_error" }, header);
        Assert.Equal(0.5 * Math.Sin(2 * Math.PI / 3), rows[0][1], 1e-15);
        Assert.Equal(120, rows[0][11], 1e-12);
        Assert.All(rows, r => Assert.True(r[15] < 1e-9, $"rod error {r[15]}"));
        Assert.All(rows, r => Assert.True(Math.Abs(r[11] - r[12]) < 1e-6, $"angle {r[11]} against {r[12]}"));
    }

    [Fact]
    public void The_hanging_chains_summary_gives_its_distance_from_the_discrete_catenary()
    {
        var result = DemoProcess.Run("hanging-chain");

        Assert.True(result.ExitCode == 0, result.Error);
        var summary = result.OutputLines[^1];
        var distance = double.Parse(
            System.Text.RegularExpressions.Regex.Match(summary, "catenary_distance = ([^,]+),").Groups[1].Value, CultureInfo.InvariantCulture);
        Assert.True(distance < 1e-4, summary);
        Assert.StartsWith("final state at t = 20 s: y5 = -0.592", summary, StringComparison.Ordinal);
    }

    [Fact]
    public void The_hanging_chain_under_xpbd_says_its_substeps_and_stays_within_1e_3()
    {
        var result = DemoProcess.Run("hanging-chain", "--integrator", "xpbd", "--substeps", "20", "--particles", "21", "--format", "json");

        Assert.True(result.ExitCode == 0, result.Error);
        Assert.Contains("\"substeps\": 20,", result.Output, StringComparison.Ordinal);
        Assert.Contains("\"particles\": 21", result.Output, StringComparison.Ordinal);
        var final = result.Output[result.Output.IndexOf("\"final\"", StringComparison.Ordinal)..];
        var distance = double.Parse(
            System.Text.RegularExpressions.Regex.Match(final, "\"catenary_distance\": ([^,}]+)").Groups[1].Value, CultureInfo.InvariantCulture);
        Assert.True(distance < 1e-3, final);
    }

    [Theory]
    [InlineData("free-fall")]
    [InlineData("mass-spring-damper")]
    [InlineData("two-mass-chain")]
    [InlineData("cloth")]
    [InlineData("pendulum")]
    [InlineData("hanging-chain")]
    public void Every_particle_scenario_runs_under_xpbd_with_its_substeps(string scenario)
    {
        var result = DemoProcess.Run(scenario, "--integrator", "xpbd", "--substeps", "3", "--duration", "0.05", "--dt", "0.01");

        Assert.True(result.ExitCode == 0, result.Error);
        Assert.StartsWith($"{scenario}: xpbd (3 substeps), dt = 0.01 s", result.OutputLines[0], StringComparison.Ordinal);
    }

    [Fact]
    public void The_cloth_stays_stable_at_60_hz_under_xpbd_where_rk4_diverges()
    {
        var xpbd = DemoProcess.Run("cloth", "--integrator", "xpbd", "--dt", "0.0166667", "--duration", "5", "--stiffness", "5000");
        var rk4 = DemoProcess.Run("cloth", "--integrator", "rk4", "--dt", "0.0166667", "--duration", "5", "--stiffness", "5000");

        Assert.True(xpbd.ExitCode == 0, xpbd.Error);
        Assert.Equal(3, rk4.ExitCode);
    }

    [Fact]
    public void Convergence_pendulum_shows_orders_1_1_1_2_and_4()
    {
        var result = DemoProcess.Run("convergence", "pendulum", "--format", "csv");

        Assert.True(result.ExitCode == 0, result.Error);
        var last = result.OutputLines.Skip(1).Select(l => l.Split(',')).GroupBy(r => r[0]).ToDictionary(g => g.Key, g => g.Last());
        foreach (var (name, order) in new[] { ("explicit-euler", 1), ("semi-implicit-euler", 1), ("implicit-euler", 1), ("velocity-verlet", 2), ("rk4", 4), ("xpbd", 1) })
        {
            var observed = double.Parse(last[name][4], CultureInfo.InvariantCulture);
            Assert.True(Math.Abs(observed - order) < 0.05, $"{name}: observed order {observed}, expected {order}");
        }
    }
}
