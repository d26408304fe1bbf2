using System;
using System.Linq;
using ParticlePhysics.Bodies;
using ParticlePhysics.Constraints;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Tests.Bodies;

/// <summary>Soft bodies' plasticity: a squash past the yield stays, one within it springs back, a failed step undoes it.</summary>
public class PlasticityTests
{
    private readonly Xunit.Abstractions.ITestOutputHelper _output;

    public PlasticityTests(Xunit.Abstractions.ITestOutputHelper output)
    {
        _output = output;
    }

    [Fact]
    public void A_squash_past_the_yield_stays_in_part_and_one_within_it_springs_back_with_the_rest_shape_untouched()
    {
        // A 4 x 4 x 4 soft box squashed to half its height (its outer centres 0.15 m apart instead of 0.3 m), then let go.
        var (elastic, elasticBodies) = SquashedBox(yield: 0.5);
        var (plastic, plasticBodies) = SquashedBox(yield: 0.01);
        var rest = elasticBodies.RestShapeOf(0).ToArray();
        var p0 = ShapeMatchingTests.Momentum(plastic);
        var xpbd = new Xpbd(10);
        for (var s = 0; s < 120; s++)
        {
            elastic.Step(xpbd, 1.0 / 60);
            plastic.Step(xpbd, 1.0 / 60);
        }

        var (elasticHeight, plasticHeight) = (ShapeMatchingTests.Height(elastic), ShapeMatchingTests.Height(plastic));
        _output.WriteLine($"after 2 s: elastic {elasticHeight:F4} m high, plastic (yield 1 cm, creep 0.5) {plasticHeight:F4} m; plastic shape error {RigidBodyTests.ShapeError(plastic, plasticBodies):E2} m");

        // Within the yield (every particle nearer its goal than 0.5 m): the rest shape keeps its bits and the box its size.
        Assert.Equal(rest, elasticBodies.RestShapeOf(0).ToArray());
        Assert.Equal(0.3, elasticHeight, 6);

        // Past it: the box stays squashed in part, at rest in its new shape, with its momentum kept.
        Assert.InRange(plasticHeight, 0.16, 0.28);
        Assert.True(RigidBodyTests.ShapeError(plastic, plasticBodies) < 1e-9);
        // The goals' mass-weighted mean is the centre of mass whatever the rest shape, so the projection keeps the
        // momentum; the rest shape rounded anew at each of the 1,200 projections leaves 4e-11 of it.
        Assert.True((ShapeMatchingTests.Momentum(plastic) - p0).Length < 1e-9 * p0.Length, $"momentum moved from {p0} to {ShapeMatchingTests.Momentum(plastic)}");
    }

    [Fact]
    public void A_failed_step_leaves_the_rest_shape_as_it_was_and_a_retry_takes_the_same_step()
    {
        var (world, bodies) = SquashedBox(yield: 0.01);
        var (fresh, _) = SquashedBox(yield: 0.01);
        var xpbd = new Xpbd(10);
        world.Step(xpbd, 1.0 / 60);
        fresh.Step(xpbd, 1.0 / 60);
        var rest = bodies.RestShapeOf(0).ToArray();
        world.DivergenceLimit = 1e-3; // the squash's velocities pass it: the step fails
        Assert.Throws<SimulationDivergedException>(() => world.Step(xpbd, 1.0 / 60));
        Assert.Equal(rest, bodies.RestShapeOf(0).ToArray());
        world.DivergenceLimit = double.MaxValue;
        world.Step(xpbd, 1.0 / 60);
        fresh.Step(xpbd, 1.0 / 60);
        Assert.Equal(fresh.Positions.ToArray(), world.Positions.ToArray());
        Assert.NotEqual(rest, bodies.RestShapeOf(0).ToArray());
    }

    [Fact]
    public void Bad_plasticity_is_refused_with_the_value()
    {
        var world = new ParticleWorld();
        for (var i = 0; i < 4; i++)
        {
            world.AddParticle(new Vector3d(i % 2, i / 2, 0.1 * i), 1.0);
        }

        var bodies = new ShapeMatching(world);
        bodies.AddRigid(new[] { 0, 1, 2 });
        bodies.AddSoft(new[] { 3 }, 0.5);
        Assert.Contains("rigid", Assert.Throws<ArgumentException>(() => bodies.SetPlasticity(0, 0.01, 0.5)).Message);
        foreach (var yield in new[] { 0.0, -1.0, double.NaN, double.PositiveInfinity })
        {
            Assert.Contains("yield", Assert.Throws<ArgumentOutOfRangeException>(() => bodies.SetPlasticity(1, yield, 0.5)).Message);
        }

        foreach (var creep in new[] { 0.0, 1.5, double.NaN })
        {
            Assert.Contains("(0, 1]", Assert.Throws<ArgumentOutOfRangeException>(() => bodies.SetPlasticity(1, 0.01, creep)).Message);
        }

        Assert.Equal((double.PositiveInfinity, 0.0), bodies.GetPlasticity(1));
        bodies.SetPlasticity(1, 0.01, 0.25);
        Assert.Equal((0.01, 0.25), bodies.GetPlasticity(1));
    }

    private static (ParticleWorld World, ShapeMatching Bodies) SquashedBox(double yield)
    {
        var world = new ParticleWorld();
        var points = BodyLattice.Box(Vector3d.Zero, new Vector3d(0.4, 0.4, 0.4), Rotation3d.Identity, 0.1);
        var particles = new int[points.Length];
        for (var k = 0; k < points.Length; k++)
        {
            particles[k] = world.AddParticle(points[k], new Vector3d(0.5, 0, 0), 0.1);
        }

        var bodies = new ShapeMatching(world);
        bodies.AddSoft(particles, 0.05);
        bodies.SetPlasticity(0, yield, 0.5);
        world.AddConstraints(bodies);
        for (var k = 0; k < particles.Length; k++)
        {
            var x = world.GetPosition(particles[k]);
            world.SetPosition(particles[k], new Vector3d(x.X * 1.2, x.Y * 0.5, x.Z));
        }

        return (world, bodies);
    }
}
