using System;
using System.Linq;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Tests.Demo;

/// <summary>What the demo prints follows each scenario's exact solution, computed here independently of its exact columns.</summary>
public class DemoExactSolutionTests
{
    [Fact]
    public void Free_fall_with_rk4_follows_the_course_formula()
    {
        var (header, rows) = DemoProcess.Run("free-fall", "--format", "csv").Csv();
        int y = Array.IndexOf(header, "y0"), vy = Array.IndexOf(header, "vy0");

        // tau = m / lambda = 1 s, g = 9.81, h = 300: y = h - g tau t + g tau^2 (1 - e^(-t/tau)).
        foreach (var row in rows)
        {
            var t = row[0];
            Assert.Equal(300 - (9.81 * t) + (9.81 * (1 - Math.Exp(-t))), row[y], 1e-8);
            Assert.Equal(-9.81 * (1 - Math.Exp(-t)), row[vy], 1e-8);
        }

        Assert.Equal(10.0, rows[^1][0]);
    }

    [Fact]
    public void Free_fall_without_drag_is_the_parabola()
    {
        var (header, rows) = DemoProcess.Run("free-fall", "--format", "csv", "--drag", "0", "--height", "10", "--duration", "1").Csv();
        var y = Array.IndexOf(header, "y0");

        Assert.All(rows, row => Assert.Equal(10 - (0.5 * 9.81 * row[0] * row[0]), row[y], 1e-10));
    }

    [Theory]
    [InlineData("explicit-euler", 0.5)]
    [InlineData("semi-implicit-euler", 0.05)]
    [InlineData("rk4", 1e-7)]
    [InlineData("velocity-verlet", 1e-3)]
    [InlineData("rk45", 1e-7)]
    public void Mass_spring_damper_follows_the_damped_oscillator(string integrator, double tolerance)
    {
        var result = DemoProcess.Run("mass-spring-damper", "--format", "csv", "--integrator", integrator);
        var (header, rows) = result.Csv();
        var y = Array.IndexOf(header, "y0");
        var exact = new double[6];
        var scenario = new MassSpringDamperScenario();

        Assert.Equal(0, result.ExitCode);
        foreach (var row in rows)
        {
            scenario.ExactState(row[0], exact);
            Assert.Equal(exact[1], row[y], tolerance);
        }

        // m y'' + c y' + k y = -m g settles toward y = -m g / k = -9.81: after 20 s it swings about it.
        Assert.InRange(rows.Skip(rows.Length / 2).Average(r => r[y]), -11, -8.5);
    }

    [Fact]
    public void Two_mass_chain_follows_its_matrix_exponential_and_reports_its_error()
    {
        var (header, rows) = DemoProcess.Run("two-mass-chain", "--format", "csv").Csv();
        int y0 = Array.IndexOf(header, "y0"), y1 = Array.IndexOf(header, "y1"), error = Array.IndexOf(header, "error");
        var scenario = new TwoMassChainScenario();
        var exact = new double[12];

        foreach (var row in rows.Where((_, i) => i % 20 == 0).Append(rows[^1]))
        {
            scenario.ExactState(row[0], exact);
            Assert.Equal(Math.Max(Math.Abs(exact[1] - row[y0]), Math.Abs(exact[4] - row[y1])), row[error], 1e-6);
            Assert.Equal(exact[1], row[y0], 1e-6);
            Assert.Equal(exact[4], row[y1], 1e-6);
            Assert.InRange(row[error], 0, 1e-6);
        }
    }

    [Fact]
    public void Scalar_ode_follows_e_to_the_minus_t_squared_and_its_error_column_is_the_difference()
    {
        var (_, rows) = DemoProcess.Run("scalar-ode", "--format", "csv", "--integrator", "rk4").Csv();

        foreach (var row in rows)
        {
            Assert.Equal(Math.Exp(-row[0] * row[0]), row[2], 1e-15);
            Assert.Equal(row[2], row[1], 1e-5);
            Assert.Equal(Math.Abs(row[1] - row[2]), row[3]);
        }
    }

    [Fact]
    public void The_cloth_hangs_from_its_two_pinned_corners()
    {
        var (header, rows) = DemoProcess.Run("cloth", "--format", "csv", "--duration", "1").Csv();
        var n = 11;
        int corner = Array.IndexOf(header, "y0"), otherCorner = Array.IndexOf(header, $"y{n - 1}"), far = Array.IndexOf(header, $"y{(n * n) - 1}");

        Assert.All(rows, r => Assert.Equal(0.0, r[corner]));
        Assert.All(rows, r => Assert.Equal(0.0, r[otherCorner]));
        Assert.True(rows[^1][far] < -0.3, $"the free far corner should have fallen; y = {rows[^1][far]}");
    }
}
