using System;
using System.Linq;
using ParticlePhysics.Contacts;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Tests.Contacts;

/// <summary>The cloth against a sphere and against itself.</summary>
public class DrapeTests
{
    [Fact]
    public void The_draped_cloth_never_enters_the_sphere_and_its_middle_comes_to_rest_on_top()
    {
        var scenario = new DrapeScenario();
        var cloth = scenario.BuildCloth();
        var world = cloth.System;
        var contacts = world.Constraints.OfType<ContactSet>().Single();
        var sphere = contacts.Obstacles[0];
        var rk4 = new RungeKutta4();
        var middle = cloth.ParticleIndex(cloth.Rows / 2, cloth.Columns / 2);
        for (var step = 1; step <= 3000; step++)
        {
            world.Step(rk4, DrapeScenario.DefaultTimeStep);
            if (step % 50 == 0)
            {
                for (var i = 0; i < world.Count; i++)
                {
                    var gap = sphere.SignedDistance(world.GetPosition(i), out _) - scenario.Radius;
                    Assert.True(gap >= -1e-6, $"particle {i} inside by {-gap} at step {step}");
                }

                Assert.True(Pile.WorstOverlap(world, contacts) < 0.01 * scenario.Radius, $"self-overlap at step {step}");
            }
        }

        // The middle rests on the sphere (on its surface, near its top).
        var top = scenario.SphereCenter + new Vector3d(0, scenario.SphereRadius + scenario.Radius, 0);
        Assert.True(Math.Abs(sphere.SignedDistance(world.GetPosition(middle), out _) - scenario.Radius) < 1e-6);
        Assert.True((world.GetPosition(middle) - top).Length < 0.01, $"middle at {world.GetPosition(middle)}, top {top}");
        Assert.True(world.GetVelocity(middle).Length < 0.01, $"middle still moving at {world.GetVelocity(middle)}");
        var lowest = double.PositiveInfinity;
        for (var i = 0; i < world.Count; i++)
        {
            lowest = Math.Min(lowest, world.GetPosition(i).Y);
        }

        Assert.True(lowest < scenario.SphereY, $"the cloth does not hang around the sphere: lowest {lowest}");
    }

    [Fact]
    public void A_cloth_falling_onto_itself_does_not_pass_through_itself()
    {
        // Two cloths of particle spheres, one dropped onto the other lying on the ground: self-collision by particle
        // spheres keeps every pair not joined by a spring at least the two radii apart.
        var world = new ParticleWorld();
        var lower = new ParticlePhysics.Cloth.ClothBuilder { Rows = 8, Columns = 8, Spacing = 0.05, Pinning = ParticlePhysics.Cloth.ClothPinning.None }.AddTo(world);
        var upper = new ParticlePhysics.Cloth.ClothBuilder
        {
            Rows = 8,
            Columns = 8,
            Spacing = 0.05,
            Pinning = ParticlePhysics.Cloth.ClothPinning.None,
            Origin = new Vector3d(0.02, 0.3, 0.02),
            Gravity = 0,
        }.AddTo(world);
        for (var i = 0; i < world.Count; i++)
        {
            world.SetRadius(i, 0.02);
        }

        var filter = ExcludedPairs.FromSprings(lower.Springs);
        var joined = ExcludedPairs.FromSprings(upper.Springs);
        for (var s = 0; s < upper.Springs.Count; s++)
        {
            var (a, b) = upper.Springs.GetEnds(s);
            filter.Add(a, b);
        }

        var contacts = new ContactSet { ParticleCollisions = true, PairFilter = filter };
        contacts.Add(new PlaneObstacle(new Vector3d(0, -0.02, 0), new Vector3d(0, 1, 0), 0, 0.5));
        world.AddConstraints(contacts);
        var rk4 = new RungeKutta4();
        for (var step = 1; step <= 1500; step++)
        {
            world.Step(rk4, 0.001);
            if (step % 100 == 0)
            {
                Assert.True(Pile.WorstOverlap(world, contacts) < 0.01 * 0.02, $"overlap at step {step}");
            }
        }

        for (var i = upper.FirstParticle; i < upper.FirstParticle + upper.ParticleCount; i++)
        {
            Assert.True(world.GetPosition(i).Y > 0.02, $"particle {i} of the upper cloth went through the lower one");
        }

        Assert.True(joined.Count > 0);
    }
}
