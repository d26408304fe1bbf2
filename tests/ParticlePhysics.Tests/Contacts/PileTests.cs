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
