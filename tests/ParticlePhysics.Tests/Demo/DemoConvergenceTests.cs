using System;
using System.Globalization;
using System.Linq;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Tests.Demo;

/// <summary><c>convergence SCENARIO</c> observes each integrator's order with its defaults.</summary>
public class DemoConvergenceTests
{
    [Theory]
    [InlineData("free-fall")]
    [InlineData("mass-spring-damper")]
    [InlineData("two-mass-chain")]
    [InlineData("pendulum")]
    [InlineData("scalar-ode")]
    public void The_default_settings_give_clean_orders(string scenario)
    {
        var result = DemoProcess.Run("convergence", scenario, "--format", "csv");

        Assert.Equal(0, result.ExitCode);
        Assert.Equal("integrator,dt,steps,error,order,expected_order", result.OutputLines[0]);
        var rows = result.OutputLines.Skip(1).Select(l => l.Split(',')).ToArray();
        Assert.NotEmpty(rows);
        foreach (var row in rows.Where(r => r[4].Length > 0))
        {
            var observed = double.Parse(row[4], CultureInfo.InvariantCulture);
            var expected = double.Parse(row[5], CultureInfo.InvariantCulture);
            Assert.True(Math.Abs(observed - expected) < 0.15, $"{scenario} {row[0]} at dt {row[1]}: order {observed}, expected {expected}");
        }
    }

    [Fact]
    public void Each_level_halves_dt_and_doubles_the_steps_to_the_same_end_time()
    {
        var result = DemoProcess.Run("convergence", "free-fall", "--integrator", "rk4", "--dt", "0.2", "--duration", "1", "--levels", "5", "--format", "csv");

        var rows = result.OutputLines.Skip(1).Select(l => l.Split(',')).ToArray();
        Assert.Equal(new[] { "0.2", "0.1", "0.05", "0.025", "0.0125" }, rows.Select(r => r[1]));
        Assert.Equal(new[] { "5", "10", "20", "40", "80" }, rows.Select(r => r[2]));
    }

    [Fact]
    public void The_table_lists_every_fixed_step_integrator_that_applies()
    {
        var result = DemoProcess.Run("convergence", "two-mass-chain");

        Assert.Equal(0, result.ExitCode);
        foreach (var name in IntegratorCatalog.Names.Where(n => IntegratorCatalog.Create(n) is not DormandPrince45))
        {
            Assert.Equal(4, result.OutputLines.Count(l => l.StartsWith(name + " ", StringComparison.Ordinal)));
        }

        Assert.Contains("observed order", result.OutputLines[1], StringComparison.Ordinal);
    }

    [Fact]
    public void A_level_that_diverges_is_marked_and_the_study_exits_with_3()
    {
        // Explicit Euler amplifies the oscillator at every step; at dt = 2 s it passes 1e12 long before t = 200 s.
        var result = DemoProcess.Run("convergence", "mass-spring-damper", "--dt", "2", "--duration", "200", "--integrator", "explicit-euler");

        Assert.Equal(3, result.ExitCode);
        Assert.Equal(4, result.OutputLines.Count(l => l.StartsWith("explicit-euler ", StringComparison.Ordinal)));
        Assert.Contains(result.OutputLines, l => l.StartsWith("explicit-euler ", StringComparison.Ordinal) && l.Contains("diverged", StringComparison.Ordinal));
        Assert.StartsWith("error: simulation diverged at t=", Assert.Single(result.ErrorLines), StringComparison.Ordinal);
    }
}
