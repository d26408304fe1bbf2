using System;
using ParticlePhysics.Bodies;
using ParticlePhysics.Constraints;
using ParticlePhysics.Contacts;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using Xunit;

namespace ParticlePhysics.Tests.Bodies;

/// <summary>Rigid bodies in contact: a stack that stands, a box that tips over an edge exactly when its centre of mass passes it.</summary>
public class RigidContactTests
{
    private const double Spacing = 0.1;
    private readonly Xunit.Abstractions.ITestOutputHelper _output;

    public RigidContactTests(Xunit.Abstractions.ITestOutputHelper output)
    {
        _output = output;
    }

    [Fact]
    public void A_stack_of_five_boxes_stands_for_10_s()
    {
        // Boxes of 0.2 m (2 x 2 x 2 particles of radius 0.05 m), each resting on the one below.
        var world = new ParticleWorld();
        var bodies = new ShapeMatching(world);
        var size = new Vector3d(0.2, 0.2, 0.2);
        for (var b = 0; b < 5; b++)
        {
            AddBox(world, bodies, new Vector3d(0, 0.1 + (0.2 * b), 0), size, Rotation3d.Identity, 1.0);
        }

        world.AddForce(Gravity.Down(9.81));
        var contacts = new ContactSet { ParticleCollisions = true, ParticleFriction = 0.5, PairFilter = bodies.PairFilter };
        contacts.Add(PlaneObstacle.Ground(0, 0.5));
        world.AddConstraints(bodies);
        world.AddConstraints(contacts);
        // One second to settle: the contacts, projected once per substep, hold each box a few g h_s^2 into the
        // one below (first order in the substep, as xpbd's contacts are); then the stack must not move.
        var xpbd = new Xpbd(10);
        var rest = new Vector3d[5];
        for (var step = 0; step < 60; step++)
        {
            world.Step(xpbd, 1.0 / 60);
        }

        for (var b = 0; b < 5; b++)
        {
            rest[b] = bodies.GetPose(b).Position;
        }

        var drift = 0.0;
        for (var step = 0; step < 600; step++)
        {
            world.Step(xpbd, 1.0 / 60);
            for (var b = 0; b < 5; b++)
            {
                drift = Math.Max(drift, (bodies.GetPose(b).Position - rest[b]).Length);
            }
        }

        var sag = 0.9 - bodies.GetPose(4).Position.Y;
        _output.WriteLine($"largest drift of a box's centre over 10 s after settling: {drift:E3} m; the top box sits {sag:E3} m below its stacked height");
        Assert.True(drift < 0.01 * 0.2, $"a box moved {drift:E3} m");
        Assert.True(Math.Abs(sag) < 0.01 * 0.2, $"the top box sank {sag:E3} m");
    }

    [Theory]
    [InlineData(-0.01, false)]
    [InlineData(-0.005, false)]
    [InlineData(0.005, true)]
    [InlineData(0.01, true)]
    public void A_bar_over_an_edge_tips_exactly_when_its_centre_of_mass_passes_its_last_support(double beyond, bool tips)
    {
        // A bar of 6 x 2 x 2 particles (0.6 x 0.2 x 0.2 m) on a platform whose edge is at x = 0: its fourth column of
        // particles rests at x = -0.001 m, the last support (the fifth, at 0.099 m, is clear of the corner by more than
        // its radius). Masses 1 + alpha j along the columns j put the centre of mass at -0.001 + beyond without moving
        // the lattice: sum_j (1 + alpha j)(x_j - x_s - beyond) = 0 gives alpha = 6 (0.05 + beyond) / (1 - 15 beyond).
        var world = new ParticleWorld();
        var bodies = new ShapeMatching(world);
        var alpha = 6 * (0.05 + beyond) / (1 - (15 * beyond));
        var points = BodyLattice.Box(new Vector3d(-0.051, 0.1, 0), new Vector3d(0.6, 0.2, 0.2), Rotation3d.Identity, Spacing);
        var particles = new int[points.Length];
        for (var k = 0; k < points.Length; k++)
        {
            particles[k] = world.AddParticle(points[k], 1.0 + (alpha * (k % 6)));
            world.SetRadius(particles[k], Spacing / 2);
        }

        bodies.AddRigid(particles);
        Assert.Equal(-0.001 + beyond, bodies.GetPose(0).Position.X, 12);
        world.AddForce(Gravity.Down(9.81));
        var contacts = new ContactSet { PairFilter = bodies.PairFilter };
        contacts.Add(new BoxObstacle(new Vector3d(-1, -0.5, 0), new Vector3d(1, 0.5, 1), 0, 0.8));
        world.AddConstraints(bodies);
        world.AddConstraints(contacts);
        var xpbd = new Xpbd(10);
        for (var step = 0; step < 120; step++)
        {
            world.Step(xpbd, 1.0 / 60);
        }

        var pose = bodies.GetPose(0);
        var tilt = Math.Acos(Math.Min(1.0, pose.Rotation.Rotate(new Vector3d(1, 0, 0)).X));
        _output.WriteLine($"centre of mass {beyond} m past the last support: tilt {tilt:F4} rad after 2 s, centre at y = {pose.Position.Y:F4} m");
        if (tips)
        {
            Assert.True(tilt > 0.5 && pose.Position.Y < 0, $"tilted {tilt} rad, centre at y = {pose.Position.Y} m");
        }
        else
        {
            // Resting, a bar tilts until its contacts, projected once per substep, balance: a few mrad at 600 Hz.
            Assert.True(tilt < 0.01, $"tilted {tilt} rad");
            Assert.True(Math.Abs(pose.Position.Y - 0.1) < 1e-3, $"centre at y = {pose.Position.Y} m");
        }
    }

    internal static int AddBox(ParticleWorld world, ShapeMatching bodies, Vector3d centre, Vector3d size, Rotation3d rotation, double mass)
    {
        var points = BodyLattice.Box(centre, size, rotation, Spacing);
        var particles = new int[points.Length];
        for (var k = 0; k < points.Length; k++)
        {
            particles[k] = world.AddParticle(points[k], mass / points.Length);
            world.SetRadius(particles[k], Spacing / 2);
        }

        return bodies.AddRigid(particles, rotation);
    }
}
