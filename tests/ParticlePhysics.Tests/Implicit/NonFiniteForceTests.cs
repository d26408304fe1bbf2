using System;
using ParticlePhysics.Cloth;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Implicit;

/// <summary>
/// Issue 10, item 3: implicit Euler does not hide a force that is not finite. A NaN or infinite force, right-hand side
/// or residual fails the step (SimulationDivergedException, nothing committed); a very large step either solves to
/// its tolerance or fails, never "converges" to the unchanged state.
/// </summary>
public class NonFiniteForceTests
{
    [Theory]
    [InlineData(Fault.NaN, UserForceTreatment.Explicit)]
    [InlineData(Fault.Infinity, UserForceTreatment.Explicit)]
    [InlineData(Fault.NaN, UserForceTreatment.FiniteDifference)]
    [InlineData(Fault.Infinity, UserForceTreatment.FiniteDifference)]
    public void A_force_that_is_not_finite_fails_the_step_and_names_the_particle(Fault fault, UserForceTreatment treatment)
    {
        // Before: NaN gave a "successful" step with a guessed dv, +infinity one that even reported LastConverged.
        var world = new ClothBuilder { Rows = 4, Columns = 4 }.Build().System;
        var force = new FaultyForce { Particle = 6 };
        world.AddForce(force);
        var implicitEuler = new ImplicitEuler { UserForces = treatment };
        world.Step(implicitEuler, 1.0 / 60);
        var before = world.State.ToArray();

        force.Arm(fault);
        var e = Assert.Throws<SimulationDivergedException>(() => world.Step(implicitEuler, 1.0 / 60));
        Assert.Equal(6, e.Particle);
        Assert.Contains("particle 6", e.Message, StringComparison.Ordinal);
        Assert.False(implicitEuler.LastConverged);
        Assert.Equal(before, world.State.ToArray());
        Assert.Equal(1.0 / 60, world.Time);
    }

    [Fact]
    public void A_force_that_is_not_finite_on_a_pinned_particle_changes_nothing_it_moves()
    {
        // A pinned particle's force is filtered out of the implicit system (its dv is 0 whatever acts on it).
        var world = new ClothBuilder { Rows = 3, Columns = 3 }.Build().System;
        var force = new FaultyForce { Particle = 0 };
        world.AddForce(force);
        Assert.True(world.IsPinned(0));
        force.Arm(Fault.NaN);
        var implicitEuler = new ImplicitEuler();
        world.Step(implicitEuler, 1.0 / 60);
        Assert.True(implicitEuler.LastConverged);
        Assert.All(world.State.ToArray(), v => Assert.True(double.IsFinite(v)));
    }

    [Theory]
    [InlineData(1e300)]
    [InlineData(1e200)]
    [InlineData(1e100)]
    [InlineData(1e10)]
    public void A_very_large_step_of_free_fall_either_solves_to_its_tolerance_or_fails(double h)
    {
        // Before: one step of 1e300 s from rest returned the unchanged state as converged. Backward Euler for free fall
        // with drag is exact here: v1 = (v0 - g h) / (1 + h / tau), x1 = x0 + h v1.
        var scenario = new FreeFallScenario();
        var world = scenario.Build();
        var implicitEuler = new ImplicitEuler { ThrowIfNotConverged = true };
        var failure = Record.Exception(() => world.Step(implicitEuler, h));
        if (failure is not null)
        {
            Assert.IsType<SimulationDivergedException>(failure);
            Assert.Equal(0.0, world.Time);
            Assert.Equal(scenario.Height, world.GetPosition(0).Y);
            return;
        }

        var tau = scenario.Mass / scenario.Drag;
        var v1 = -scenario.Gravity * h / (1 + (h / tau));
        Assert.True(implicitEuler.LastConverged);
        Assert.Equal(v1, world.GetVelocity(0).Y, 1e-6 * Math.Abs(v1));
        Assert.Equal(scenario.Height + (h * v1), world.GetPosition(0).Y, 1e-6 * Math.Abs(h * v1));
    }

    [Fact]
    public void One_step_of_1e300_seconds_fails_rather_than_returning_the_unchanged_state()
    {
        var world = new FreeFallScenario().Build();
        var implicitEuler = new ImplicitEuler();
        var e = Assert.Throws<SimulationDivergedException>(() => world.Step(implicitEuler, 1e300));
        Assert.Contains("too large", e.Message, StringComparison.Ordinal);
        Assert.False(implicitEuler.LastConverged);

        var cloth = new ClothScenario().Build();
        var before = cloth.State.ToArray();
        Assert.Throws<SimulationDivergedException>(() => cloth.Step(implicitEuler, 1e300));
        Assert.Equal(before, cloth.State.ToArray());
    }
}
