using System;
using ParticlePhysics.Contacts;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Tests.Contacts;

/// <summary>A particle's own friction and restitution meet the other side's by their mean (SCENES.md, as Unity by default).</summary>
public class ParticleMaterialTests
{
    [Fact]
    public void A_particles_own_restitution_meets_the_obstacles_by_their_mean()
    {
        // NaN twice: no material of its own; a friction of its own without a restitution: the obstacle's restitution alone.
        foreach (var (friction, own, expected) in new[] { (double.NaN, double.NaN, 0.2), (0.7, double.NaN, 0.2), (0.0, 1.0, 0.6), (0.0, 0.0, 0.1) })
        {
            var world = new ParticleWorld();
            world.AddParticle(new Vector3d(0, 0.05, 0), new Vector3d(0, -1, 0), 1.0);
            var contacts = new ContactSet();
            contacts.Add(PlaneObstacle.Ground(restitution: 0.2));
            contacts.SetParticleMaterial(0, 1, friction, own);

            world.AddConstraints(contacts);
            world.Step(new SemiImplicitEuler(), 0.1);
            Assert.Equal(expected, world.GetVelocity(0).Y, 15);
        }
    }

    [Fact]
    public void A_slide_on_a_particles_own_friction_stops_after_v0_squared_over_2_mu_g_with_the_mean_mu()
    {
        const double g = 9.81;
        var world = new ParticleWorld();
        world.AddParticle(Vector3d.Zero, new Vector3d(2, 0, 0), 1.0);
        world.AddForce(Gravity.Down(g));
        var contacts = new ContactSet();
        contacts.Add(PlaneObstacle.Ground(friction: 0.2));
        contacts.SetParticleMaterial(0, 1, 0.6, 0.0);
        world.AddConstraints(contacts);
        for (var s = 0; s < 1000; s++)
        {
            world.Step(new SemiImplicitEuler(), 0.001);
        }

        Assert.Equal(4.0 / (2 * 0.4 * g), world.GetPosition(0).X, 9);
        Assert.Equal(0.0, world.GetVelocity(0).X, 15);
    }

    [Fact]
    public void Pairs_meet_by_the_mean_of_their_own_or_the_sets_values_and_bad_materials_are_refused()
    {
        var contacts = new ContactSet { ParticleRestitution = 0.4 };
        contacts.SetParticleMaterial(2, 3, 0.5, 1.0);
        Assert.Null(contacts.GetParticleMaterial(1));
        Assert.Equal((0.5, 1.0), contacts.GetParticleMaterial(4));
        Assert.Null(contacts.GetParticleMaterial(5));
        contacts.SetParticleMaterial(6, 1, double.NaN, double.NaN);
        Assert.Null(contacts.GetParticleMaterial(6));
        contacts.SetParticleMaterial(6, 1, 0.3, double.NaN);
        Assert.Equal(0.3, contacts.GetParticleMaterial(6)!.Value.Friction);
        Assert.True(double.IsNaN(contacts.GetParticleMaterial(6)!.Value.Restitution));
        Assert.Contains("-1", Assert.Throws<ArgumentOutOfRangeException>(() => contacts.SetParticleMaterial(0, 1, -1, 0)).Message);
        Assert.Contains("1.5", Assert.Throws<ArgumentOutOfRangeException>(() => contacts.SetParticleMaterial(0, 1, 0, 1.5)).Message);

        // Head-on, equal masses, radius 0.1: restitution (0.4 + 1.0) / 2 = 0.7 between particle 1 (the set's) and 2 (its own).
        var world = new ParticleWorld();
        for (var i = 0; i < 3; i++)
        {
            world.AddParticle(new Vector3d(-10 * (i + 1), 0, 0), 1.0);
        }

        world.SetPosition(1, new Vector3d(0, 0, 0));
        world.SetVelocity(1, new Vector3d(1, 0, 0));
        world.SetPosition(2, new Vector3d(0.25, 0, 0));
        world.SetVelocity(2, new Vector3d(-1, 0, 0));
        world.SetRadius(1, 0.1);
        world.SetRadius(2, 0.1);
        contacts.ParticleCollisions = true;
        world.AddConstraints(contacts);
        world.Step(new SemiImplicitEuler(), 0.1);
        Assert.Equal(-0.7, world.GetVelocity(1).X, 14);
        Assert.Equal(0.7, world.GetVelocity(2).X, 14);
    }
}
