using System;
using System.Linq;
using ParticlePhysics.Contacts;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Tests.Contacts;

/// <summary>A pile of 1,000 particles in a box settles, overlapping by less than 1 % of the radius and staying out of the walls.</summary>
public class PileTests
{
    [Fact]
    public void A_pile_of_1000_particles_in_a_box_settles_with_overlaps_below_1_percent_of_the_radius()
    {
        var scenario = new ParticleBoxScenario { Count = 1000 };
        var world = scenario.Build();
        var contacts = world.Constraints.OfType<ContactSet>().Single();
        var rk4 = new RungeKutta4();
        var worstOverlap = 0.0;
        for (var step = 1; step <= 1000; step++)
        {
            world.Step(rk4, 0.001);
            if (step % 100 == 0)
            {
                worstOverlap = Math.Max(worstOverlap, Pile.WorstOverlap(world, contacts) / scenario.Radius);
            }
        }

        Assert.True(worstOverlap < 0.01, $"overlap {worstOverlap:P3} of the radius");
        var fastest = 0.0;
        for (var i = 0; i < world.Count; i++)
        {
            fastest = Math.Max(fastest, world.GetVelocity(i).Length);
            Assert.True(world.GetPosition(i).Y >= scenario.Radius - 1e-6);
        }

        Assert.True(fastest < 0.01, $"still moving at {fastest} m/s");
    }

    [Fact]
    public void At_60_Hz_the_pile_stays_within_1_percent_overlap_at_the_default_passes()
    {
        // A frame per step: 14 times the 1 ms step's sinking per step for the separation to undo.
        var scenario = new ParticleBoxScenario { Count = 1000 };
        var world = scenario.Build();
        var contacts = (ContactSet)world.Constraints[0];
        var rk4 = new RungeKutta4();
        var worst = 0.0;
        for (var step = 1; step <= 120; step++)
        {
            world.Step(rk4, 1.0 / 60.0);
            if (step % 15 == 0)
            {
                worst = Math.Max(worst, Pile.WorstOverlap(world, contacts) / scenario.Radius);
            }
        }

        Assert.True(worst < 0.01, $"overlap {worst:P3} of the radius");
    }

    [Theory]
    [InlineData(100, 0.5)]
    [InlineData(50, 0.5)]
    [InlineData(100, 0.0)]
    [InlineData(50, 0.0)]
    public void Particles_spawned_at_one_point_separate_and_settle_without_jitter(int count, double mu)
    {
        // Issue 27, item 8: 100 particles spawned at one point, semi-implicit Euler at 60 Hz: after 10 s (and 20 s) they
        // still overlapped by the whole radius, 25 pairs exactly coincident, and the kinetic energy churned. Every
        // coincident pair was pushed apart along +y, so they could only ever spread into a column (50 did, and stood).
        const double r = 0.01;
        var world = new ParticleWorld();
        for (var i = 0; i < count; i++)
        {
            world.AddParticle(new Vector3d(0, 0.5, 0), 1);
            world.SetRadius(i, r);
        }

        world.AddForce(Forces.Gravity.Down(9.81));
        var contacts = new ContactSet { ParticleCollisions = true, ParticleFriction = mu };
        contacts.Add(PlaneObstacle.Ground(0, mu));
        world.AddConstraints(contacts);
        FrictionTests.StepFor(world, "semi-implicit-euler", 1.0 / 60.0, 10.0);
        var settled = world.State.ToArray();
        var energy = 0.0;
        foreach (var time in new[] { 10, 20 })
        {
            if (time == 20)
            {
                FrictionTests.StepFor(world, "semi-implicit-euler", 1.0 / 60.0, 10.0);
            }

            var overlap = Pile.WorstOverlap(world, contacts) / r;
            Assert.True(overlap < 0.01, $"{count} particles at {time} s: overlap {overlap:P2} of the radius");
            Assert.True(Enumerable.Range(0, count).All(i => world.GetPosition(i).Y >= r - 1e-6), "below the ground");
            Assert.True(Enumerable.Range(0, count).All(i => Math.Abs(world.GetVelocity(i).Y) < 1e-9), "bouncing");
            var kinetic = Enumerable.Range(0, count).Sum(i => 0.5 * world.Masses[i] * Vector3d.Dot(world.GetVelocity(i), world.GetVelocity(i)));
            if (mu > 0)
            {
                Assert.True(kinetic == 0.0, $"{count} particles at {time} s: {kinetic} J of kinetic energy");
            }
            else
            {
                // Without friction nothing stops them sliding apart on the ground; nothing may speed them up either.
                Assert.True(time == 10 || kinetic <= energy, $"{count} particles: {energy} J at 10 s, {kinetic} J at 20 s");
                energy = kinetic;
            }
        }

        if (mu > 0)
        {
            // Still from 10 s to 20 s, to the rounding of a coordinate near the ground.
            var moved = Enumerable.Range(0, 6 * count).Max(k => Math.Abs(world.State[k] - settled[k]));
            Assert.True(moved < 1e-12, $"moved {moved} between 10 s and 20 s");
        }
    }

    [Fact]
    public void A_column_of_ten_rests_without_jitter_even_at_60_Hz()
    {
        foreach (var dt in new[] { 0.001, 1.0 / 60.0 })
        {
            var world = new ParticleWorld();
            const double r = 0.05;
            for (var i = 0; i < 10; i++)
            {
                world.AddParticle(new Vector3d(0, (1.1 * r) + (i * 2.2 * r), 0), 0.01);
                world.SetRadius(i, r);
            }

            world.AddForce(Forces.Gravity.Down(9.81));
            var contacts = new ContactSet { ParticleCollisions = true };
            contacts.Add(PlaneObstacle.Ground());
            world.AddConstraints(contacts);
            FrictionTests.StepFor(world, "rk4", dt, 1.0);
            for (var i = 0; i < 10; i++)
            {
                Assert.Equal(r + (2 * r * i), world.GetPosition(i).Y, 12);
                Assert.True(world.GetVelocity(i).Length < 1e-12, $"dt {dt}: particle {i} at {world.GetVelocity(i)}");
            }
        }
    }
}

/// <summary>Measures of a pile.</summary>
internal static class Pile
{
    /// <summary>The largest overlap of two particles (brute force over all pairs), in metres; 0 when none touch.</summary>
    public static double WorstOverlap(ParticleWorld world, ContactSet contacts)
    {
        var worst = 0.0;
        for (var i = 0; i < world.Count; i++)
        {
            for (var j = i + 1; j < world.Count; j++)
            {
                var overlap = world.GetRadius(i) + world.GetRadius(j) - (world.GetPosition(i) - world.GetPosition(j)).Length;
                if (contacts.PairFilter?.MayCollide(i, j) ?? true)
                {
                    worst = Math.Max(worst, overlap);
                }
            }
        }

        return worst;
    }
}
