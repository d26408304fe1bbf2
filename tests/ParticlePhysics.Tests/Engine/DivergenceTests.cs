using System;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Engine;

/// <summary>A step whose result is not finite throws and leaves the last finite state in place.</summary>
public class DivergenceTests
{
    [Theory]
    [InlineData("rk4")]
    [InlineData("explicit-euler")]
    [InlineData("semi-implicit-euler")]
    [InlineData("velocity-verlet")]
    public void The_default_cloth_at_one_60_hz_frame_diverges_and_keeps_its_last_finite_state(string integrator)
    {
        var system = new ClothScenario().Build();
        var method = IntegratorCatalog.Create(integrator);
        const double dt = 1.0 / 60;
        double[] lastGood = system.State.ToArray();
        var lastTime = 0.0;
        SimulationDivergedException? diverged = null;
        for (var step = 0; step < 600 && diverged is null; step++)
        {
            try
            {
                system.Step(method, dt);
                lastGood = system.State.ToArray();
                lastTime = system.Time;
            }
            catch (SimulationDivergedException ex)
            {
                diverged = ex;
            }
        }

        Assert.NotNull(diverged);
        Assert.True(diverged.Time < 10, $"{integrator} diverged only at t={diverged.Time}");
        Assert.Equal(lastTime, system.Time);
        Assert.Equal(lastTime, diverged.LastFiniteTime);
        Assert.Equal(lastTime + dt, diverged.Time, 12);
        Assert.Equal(StateMetrics.BitHash(lastGood), StateMetrics.BitHash(system.State));
        Assert.InRange(diverged.Particle, 0, system.Count - 1);
        Assert.Contains($"particle {diverged.Particle}", diverged.Message, StringComparison.Ordinal);
        Assert.Contains("t=", diverged.Message, StringComparison.Ordinal);
        Assert.EndsWith("retry with a smaller time step, or with ImplicitEuler (implicit-euler), which stays stable at large steps.", diverged.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Rk4_on_the_default_cloth_at_60_hz_is_far_gone_within_a_quarter_second_and_reported_soon_after()
    {
        var system = new ClothScenario().Build();
        var rk4 = new RungeKutta4();
        StateMetrics.Run(system, rk4, 1.0 / 60, 15);
        var largest = 0.0;
        foreach (var x in system.Positions)
        {
            largest = Math.Max(largest, Math.Abs(x));
        }

        Assert.True(largest > 1e3, $"after 0.25 s the 1 m cloth should have blown up; largest coordinate {largest}");
        var ex = Assert.Throws<SimulationDivergedException>(() => StateMetrics.Run(system, rk4, 1.0 / 60, 60));
        Assert.True(ex.Time < 0.5, $"reported at t={ex.Time}");
        Assert.True(Math.Abs(ex.Value) > system.DivergenceLimit);
        Assert.Contains("divergence limit", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void A_free_fall_from_1e12_m_runs_because_positions_may_take_any_finite_value()
    {
        // Issue 10, item 11: the limit used to bound coordinates at 1e12 m, so this valid world "diverged" at step 1.
        var scenario = new FreeFallScenario { Height = 1.1e12 };
        var system = scenario.Build();
        StateMetrics.Run(system, new RungeKutta4(), 0.01, 1000);
        var exact = new double[system.Dimension];
        scenario.ExactState(system.Time, exact);
        Assert.Equal(exact[1], system.GetPosition(0).Y, 1.0); // 1000 roundings at 1.2e-4 m apart (an ulp at 1.1e12 m)
        Assert.Equal(exact[4], system.GetVelocity(0).Y, 1e-9);

        var far = new FreeFallScenario { Height = -1.7e308, Drag = 0 }.Build();
        StateMetrics.Run(far, new ExplicitEuler(), 0.01, 10);
    }

    [Theory]
    [InlineData(0.0)]
    [InlineData(1.1e12)]
    public void A_cloth_that_blows_up_is_caught_within_half_a_second_wherever_it_hangs(double offset)
    {
        // The same blow-up as above, with the cloth at the origin and 1.1e12 m away: caught by its speeds, early,
        // with a finite last good state (not at the overflow to infinity, seconds later).
        var system = new ClothScenario().Build();
        if (offset != 0)
        {
            var shifted = system.State.ToArray();
            for (var k = 0; k < system.CoordinateCount; k += 3)
            {
                shifted[k] += offset;
            }

            system.SetState(shifted);
        }

        var ex = Assert.Throws<SimulationDivergedException>(() => StateMetrics.Run(system, new RungeKutta4(), 1.0 / 60, 600));
        Assert.True(ex.Time < 0.5, $"reported at t={ex.Time}");
        Assert.True(double.IsFinite(ex.Value) && Math.Abs(ex.Value) > ParticleWorld.DefaultDivergenceLimit);
        Assert.True(ex.Component >= system.CoordinateCount, "the bound is on the velocities");
        Assert.Contains($"particle {ex.Particle} reached v", ex.Message, StringComparison.Ordinal);
        Assert.All(system.State.ToArray(), v => Assert.True(double.IsFinite(v)));
    }

    [Fact]
    public void Without_a_limit_only_non_finite_values_count_as_divergence()
    {
        var system = new ClothScenario().Build();
        system.DivergenceLimit = double.MaxValue;
        var ex = Assert.Throws<SimulationDivergedException>(() => StateMetrics.Run(system, new RungeKutta4(), 1.0 / 60, 600));
        Assert.False(double.IsFinite(ex.Value));
        Assert.True(ex.Time > 0.5, $"non-finite already at t={ex.Time}");
        Assert.Contains("no longer finite", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void The_caller_can_retry_with_a_smaller_step_and_nothing_is_lost()
    {
        var system = new ClothScenario().Build();
        var rk4 = new RungeKutta4();
        Assert.Throws<SimulationDivergedException>(() => StateMetrics.Run(system, rk4, 1.0 / 60, 60));
        var resumedAt = system.Time;
        StateMetrics.Run(system, rk4, 0.001, 100);
        Assert.Equal(resumedAt + 0.1, system.Time, 9);
        Assert.Equal(-1, DoubleChecksProbe(system.State));
    }

    [Fact]
    public void A_plain_ode_that_blows_up_names_the_component_and_keeps_its_state()
    {
        var simulation = new OdeSimulation(new Quadratic(), new[] { 1.0 });
        var euler = new ExplicitEuler();
        var ex = Assert.Throws<SimulationDivergedException>(() =>
        {
            for (var s = 0; s < 100; s++)
            {
                simulation.Step(euler, 1.0);
            }
        });
        Assert.Equal(-1, ex.Particle);
        Assert.Equal(0, ex.Component);
        Assert.True(double.IsFinite(simulation.State[0]) && simulation.State[0] > 1e100);
        Assert.Equal(ex.LastFiniteTime, simulation.Time);
    }

    private static int DoubleChecksProbe(ReadOnlySpan<double> values)
    {
        for (var i = 0; i < values.Length; i++)
        {
            if (!double.IsFinite(values[i]))
            {
                return i;
            }
        }

        return -1;
    }

    /// <summary>dy/dt = y^2, which explicit Euler with dt = 1 takes to infinity in a dozen steps.</summary>
    private sealed class Quadratic : IOdeSystem
    {
        public int Dimension => 1;

        public void Evaluate(double time, ReadOnlySpan<double> state, Span<double> derivative) =>
            derivative[0] = state[0] * state[0];
    }
}
