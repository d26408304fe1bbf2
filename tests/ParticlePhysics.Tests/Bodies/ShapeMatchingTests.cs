using System;
using ParticlePhysics.Bodies;
using ParticlePhysics.Constraints;
using ParticlePhysics.Contacts;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Parallel;
using ParticlePhysics.Tests.Support;
using Xunit;

namespace ParticlePhysics.Tests.Bodies;

/// <summary>The shape-matching set as an API: refusals that change nothing, failed steps, allocations, threads, soft bodies.</summary>
public class ShapeMatchingTests
{
    [Fact]
    public void Bad_bodies_are_refused_with_the_value_and_the_set_is_unchanged()
    {
        var world = new ParticleWorld();
        for (var i = 0; i < 4; i++)
        {
            world.AddParticle(new Vector3d(i, i * i, 0), 1.0);
        }

        world.AddParticle(new Vector3d(0, 0, 1), 1.0);
        var bodies = new ShapeMatching(world);
        bodies.AddRigid(new[] { 0, 1, 2 });
        Assert.Contains("none was listed", Assert.Throws<ArgumentException>(() => bodies.AddRigid(ReadOnlySpan<int>.Empty)).Message);
        Assert.Contains("already belongs to body 0", Assert.Throws<ArgumentException>(() => bodies.AddRigid(new[] { 3, 2 })).Message);
        Assert.Contains("listed twice", Assert.Throws<ArgumentException>(() => bodies.AddSoft(new[] { 3, 3 }, 0.5)).Message);
        Assert.Contains("5", Assert.Throws<ArgumentOutOfRangeException>(() => bodies.AddRigid(new[] { 3, 5 })).Message);
        Assert.Contains("one line", Assert.Throws<ArgumentException>(() => bodies.AddRigid(new[] { 4, 3 })).Message);
        foreach (var stiffness in new[] { 0.0, -0.1, 1.5, double.NaN })
        {
            Assert.Contains("(0, 1]", Assert.Throws<ArgumentOutOfRangeException>(() => bodies.AddSoft(new[] { 3, 4 }, stiffness)).Message);
        }

        Assert.Contains("0 to 0", Assert.Throws<ArgumentOutOfRangeException>(() => bodies.GetPose(1)).Message);
        Assert.Equal(1, bodies.Count);
        Assert.Equal(-1, bodies.BodyOfParticle(3));
        Assert.Equal(1, bodies.AddSoft(new[] { 3, 4 }, 0.5)); // a soft body may be a line
    }

    [Fact]
    public void A_failed_step_leaves_the_bodies_as_they_were_and_a_retry_takes_the_same_step()
    {
        var (world, bodies) = SpinningBox();
        var (fresh, freshBodies) = SpinningBox();
        var xpbd = new Xpbd(10);
        for (var s = 0; s < 10; s++)
        {
            world.Step(xpbd, 1.0 / 60);
            fresh.Step(xpbd, 1.0 / 60);
        }

        var before = bodies.GetPose(0);
        var positions = world.Positions.ToArray();
        world.DivergenceLimit = 1e-3; // the step's velocities pass it: the step fails
        Assert.Throws<SimulationDivergedException>(() => world.Step(xpbd, 1.0 / 60));
        Assert.Equal(positions, world.Positions.ToArray());
        AssertSamePose(before, bodies.GetPose(0));
        world.DivergenceLimit = double.MaxValue;
        world.Step(xpbd, 1.0 / 60);
        fresh.Step(xpbd, 1.0 / 60);
        Assert.Equal(fresh.Positions.ToArray(), world.Positions.ToArray());
        Assert.Equal(fresh.Velocities.ToArray(), world.Velocities.ToArray());
        AssertSamePose(freshBodies.GetPose(0), bodies.GetPose(0));
    }

    [Fact]
    public void A_step_allocates_nothing()
    {
        var (world, _) = SpinningBox();
        var xpbd = new Xpbd(10);
        world.Step(xpbd, 1.0 / 60);
        Assert.Equal(0, ThreadAllocations.Measure(() =>
        {
            for (var s = 0; s < 10; s++)
            {
                world.Step(xpbd, 1.0 / 60);
            }
        }));
    }

    [Fact]
    public void Bodies_falling_onto_each_other_give_the_same_bits_on_two_threads_as_on_one()
    {
        var (one, _) = Heap();
        var (two, _) = Heap();
        using var runner = new WorkerThreadRunner(2);
        two.Runner = runner;
        var a = new Xpbd(10);
        var b = new Xpbd(10);
        for (var s = 0; s < 60; s++)
        {
            one.Step(a, 1.0 / 60);
            two.Step(b, 1.0 / 60);
        }

        Assert.Equal(one.Positions.ToArray(), two.Positions.ToArray());
        Assert.Equal(one.Velocities.ToArray(), two.Velocities.ToArray());
    }

    [Fact]
    public void A_rigid_body_under_a_force_based_integrator_keeps_its_shape_and_spin()
    {
        var (world, bodies) = SpinningBox();
        var l0 = RigidBodyTests.AngularMomentum(world);
        var integrator = new SemiImplicitEuler();
        for (var s = 0; s < 600; s++)
        {
            world.Step(integrator, 1.0 / 600);
        }

        var l = RigidBodyTests.AngularMomentum(world);
        Assert.True(RigidBodyTests.ShapeError(world, bodies) < 1e-12);
        Assert.True((l - l0).Length < 1e-9 * l0.Length, $"L moved from {l0} to {l}");
    }

    [Fact]
    public void A_squashed_soft_body_springs_back_to_its_rest_shape_keeping_its_momentum()
    {
        var world = new ParticleWorld();
        var points = BodyLattice.Box(Vector3d.Zero, new Vector3d(0.4, 0.4, 0.4), Rotation3d.Identity, 0.1);
        var particles = new int[points.Length];
        for (var k = 0; k < points.Length; k++)
        {
            particles[k] = world.AddParticle(points[k], new Vector3d(0.5, 0, 0), 0.1 + (0.01 * k));
        }

        var bodies = new ShapeMatching(world);
        bodies.AddSoft(particles, 0.05);
        world.AddConstraints(bodies);
        var p0 = Momentum(world);

        // Squash it to half its height, then let it go.
        for (var k = 0; k < particles.Length; k++)
        {
            var x = world.GetPosition(particles[k]);
            world.SetPosition(particles[k], new Vector3d(x.X * 1.2, x.Y * 0.5, x.Z));
        }

        var squashed = Height(world);
        var squashedError = RigidBodyTests.ShapeError(world, bodies);
        var xpbd = new Xpbd(10);
        for (var s = 0; s < 120; s++)
        {
            world.Step(xpbd, 1.0 / 60);
        }

        Assert.Equal(0.15, squashed, 12); // 4 particles a side: 0.3 m between the outer centres at rest
        // Each substep moves the deviation e from the goals to (1 - s)(e + h u), so |e| shrinks by sqrt(1 - s) per
        // substep: by 1e-13 over 1200 substeps at s = 0.05. (The goals turn as well: the best-fit rotation of a squashed
        // body with uneven masses is not the identity, so the body comes back turned; its shape is what must return.)
        var error = RigidBodyTests.ShapeError(world, bodies);
        Assert.True(squashedError > 0.05 && error < 1e-9, $"{error:E3} m from the rest shape after 2 s; {squashedError:E3} m squashed");
        Assert.True((Momentum(world) - p0).Length < 1e-11 * p0.Length, $"momentum moved from {p0} to {Momentum(world)}");
    }

    private static (ParticleWorld World, ShapeMatching Bodies) SpinningBox()
    {
        var (world, bodies) = RigidBodyTests.Box(new Vector3d(0.4, 0.3, 0.2));
        world.AddForce(Gravity.Down(9.81));
        bodies.SetMotion(0, new Vector3d(0.5, 3, 0), new Vector3d(1, 2, 3));
        return (world, bodies);
    }

    private static (ParticleWorld World, ShapeMatching Bodies) Heap()
    {
        var world = new ParticleWorld();
        var bodies = new ShapeMatching(world);
        for (var b = 0; b < 6; b++)
        {
            var rotation = new Rotation3d(0.1 * b, 0.2, -0.1 * b, 1);
            var box = RigidContactTests.AddBox(world, bodies, new Vector3d(0.05 * b, 0.2 + (0.35 * b), 0.03 * b), new Vector3d(0.3, 0.2, 0.2), rotation, 1.0);
            Assert.Equal(b, box);
        }

        world.AddForce(Gravity.Down(9.81));
        var contacts = new ContactSet { ParticleCollisions = true, ParticleFriction = 0.4, PairFilter = bodies.PairFilter };
        contacts.Add(PlaneObstacle.Ground(0, 0.5));
        world.AddConstraints(bodies);
        world.AddConstraints(contacts);
        return (world, bodies);
    }

    private static void AssertSamePose(BodyPose expected, BodyPose actual)
    {
        Assert.Equal(expected.Position, actual.Position);
        Assert.Equal(expected.Rotation, actual.Rotation);
        Assert.Equal(expected.LinearVelocity, actual.LinearVelocity);
        Assert.Equal(expected.AngularVelocity, actual.AngularVelocity);
    }

    internal static Vector3d Momentum(ParticleWorld world)
    {
        var p = Vector3d.Zero;
        for (var i = 0; i < world.Count; i++)
        {
            p += world.GetMass(i) * world.GetVelocity(i);
        }

        return p;
    }

    internal static double Height(ParticleWorld world)
    {
        double low = double.MaxValue, high = double.MinValue;
        for (var i = 0; i < world.Count; i++)
        {
            low = Math.Min(low, world.GetPosition(i).Y);
            high = Math.Max(high, world.GetPosition(i).Y);
        }

        return high - low;
    }
}
