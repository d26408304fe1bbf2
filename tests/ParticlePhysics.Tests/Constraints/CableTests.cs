using System;
using ParticlePhysics.Constraints;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Constraints;

/// <summary>A cable is slack below its length and a rod at it; going taut is an inelastic impact.</summary>
public class CableTests
{
    [Theory]
    [InlineData("rk4")]
    [InlineData("velocity-verlet")]
    [InlineData("xpbd")]
    public void A_slack_cable_does_nothing(string integrator)
    {
        // Inside its length, a particle thrown sideways flies its parabola as if the cable were not there.
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(0, 0.1, 0), new Vector3d(0.4, 1, 0), 1);
        world.AddForce(new Gravity());
        var cables = new RodNetwork(world);
        cables.AddAnchoredCable(0, Vector3d.Zero, 1);
        world.AddConstraints(cables);
        StateMetrics.Run(world, IntegratorCatalog.Create(integrator), 0.01, 30);
        Assert.Equal(0.4 * 0.3, world.GetPosition(0).X, 1e-12);
        Assert.Equal(0.1 + 0.3 - (0.5 * 9.81 * 0.09), world.GetPosition(0).Y, integrator == "rk4" ? 1e-12 : 2e-2);
        Assert.Equal(0, cables.GetTension(0));
    }

    [Theory]
    [InlineData("explicit-euler")]
    [InlineData("semi-implicit-euler")]
    [InlineData("implicit-euler")]
    [InlineData("rk4")]
    [InlineData("velocity-verlet")]
    [InlineData("rk45")]
    [InlineData("xpbd")]
    public void A_mass_dropped_on_a_cable_stops_at_its_length_without_bouncing(string integrator)
    {
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(0, -0.2, 0), 2);
        world.AddForce(new Gravity());
        var cables = new RodNetwork(world);
        cables.AddAnchoredCable(0, Vector3d.Zero, 1);
        world.AddConstraints(cables);
        var stepper = IntegratorCatalog.Create(integrator);
        var taut = false;
        for (var s = 0; s < 2000; s++)
        {
            world.Step(stepper, 1e-3);
            var length = world.GetPosition(0).Length;
            Assert.True(length <= 1 + 1e-12, $"step {s}: the cable stretched to {length:R}");
            taut |= length > 1 - 1e-12;
            if (taut)
            {
                // e = 0: once taut the mass never rises again and keeps no speed.
                Assert.True(world.GetPosition(0).Y <= -1 + 1e-12, $"step {s}: bounced to y = {world.GetPosition(0).Y:R}");
                Assert.True(world.GetVelocity(0).Length < 1e-12, $"step {s}: moving at {world.GetVelocity(0)}");
            }
        }

        Assert.True(taut);
        if (integrator != "xpbd")
        {
            // Taut, it is a rod: it holds the weight (xpbd has no forces to report).
            Assert.Equal(2 * 9.81, cables.GetTension(0), 1e-9);
        }
    }

    [Theory]
    [InlineData("rk4")]
    [InlineData("xpbd")]
    public void A_taut_cable_swings_like_a_rod_and_goes_slack_when_it_would_have_to_push(string integrator)
    {
        // Launched along the circle from the bottom too slowly to loop, a mass on a cable leaves the circle where the
        // tension would turn negative, and falls inside it.
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(0, -1, 0), new Vector3d(6, 0, 0), 1);
        world.AddForce(new Gravity());
        var cables = new RodNetwork(world);
        cables.AddAnchoredCable(0, Vector3d.Zero, 1);
        world.AddConstraints(cables);
        var stepper = IntegratorCatalog.Create(integrator);
        var inside = false;
        for (var s = 0; s < 1500; s++)
        {
            world.Step(stepper, 1e-3);
            inside |= world.GetPosition(0).Length < 0.99;
            Assert.True(world.GetPosition(0).Length <= 1 + 1e-12);
        }

        // v0^2 = 36 < 5 g L = 49: not enough to loop; 34 degrees above the horizontal the cable goes slack.
        Assert.True(inside, "the mass never left the circle");
    }

    [Fact]
    public void A_cable_moving_inward_at_its_length_is_left_alone()
    {
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(1, 0, 0), new Vector3d(-2, 0, 0), 1);
        world.AddForce(new Gravity(new Vector3d(3, 0, 0)));
        var cables = new RodNetwork(world);
        cables.AddAnchoredCable(0, Vector3d.Zero, 1);
        world.AddConstraints(cables);
        world.Step(new RungeKutta4(), 0.1);
        Assert.Equal(1 - 0.2 + (0.5 * 3 * 0.01), world.GetPosition(0).X, 1e-12);
        Assert.Equal(0, cables.GetTension(0));
    }
}
