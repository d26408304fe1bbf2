using System;
using System.Collections.Generic;
using ParticlePhysics.Contacts;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Tests.Contacts;

/// <summary>The obstacles: their signed distances and normals, no tunnelling at 1000 m/s, and nothing inside by more than 1e-6 m.</summary>
public class ObstacleTests
{
    public static IEnumerable<object[]> Shapes()
    {
        yield return new object[] { "plane" };
        yield return new object[] { "sphere" };
        yield return new object[] { "capsule" };
        yield return new object[] { "box" };
    }

    [Theory]
    [MemberData(nameof(Shapes))]
    public void The_normal_is_the_gradient_of_the_signed_distance_which_is_1_Lipschitz(string kind)
    {
        var obstacle = Make(kind);
        var state = 12345u;
        for (var k = 0; k < 2000; k++)
        {
            var p = new Vector3d(Next(ref state) * 3, Next(ref state) * 3, Next(ref state) * 3);
            var d = obstacle.SignedDistance(p, out var normal);
            Assert.Equal(1.0, normal.Length, 12);
            const double h = 1e-6;
            var gradient = new Vector3d(
                (obstacle.SignedDistance(p + new Vector3d(h, 0, 0), out _) - obstacle.SignedDistance(p - new Vector3d(h, 0, 0), out _)) / (2 * h),
                (obstacle.SignedDistance(p + new Vector3d(0, h, 0), out _) - obstacle.SignedDistance(p - new Vector3d(0, h, 0), out _)) / (2 * h),
                (obstacle.SignedDistance(p + new Vector3d(0, 0, h), out _) - obstacle.SignedDistance(p - new Vector3d(0, 0, h), out _)) / (2 * h));
            if (Math.Abs(gradient.Length - 1) < 1e-6)
            {
                // Away from the ridges where the nearest feature changes, the normal is the gradient.
                Assert.True((gradient - normal).Length < 1e-6, $"{kind} at {p}: normal {normal}, gradient {gradient}");
            }

            // Moving along the normal by t changes the distance by t (outside, and inside short of the medial axis).
            var q = p + (1e-3 * normal);
            Assert.True(obstacle.SignedDistance(q, out _) - d <= 1e-3 + 1e-12, $"{kind}: not 1-Lipschitz at {p}");
        }
    }

    [Fact]
    public void Distances_match_the_shapes_formulas()
    {
        Assert.Equal(2.0, new PlaneObstacle(new Vector3d(0, 1, 0), new Vector3d(0, 2, 0)).SignedDistance(new Vector3d(5, 3, -1), out _), 15);
        Assert.Equal(-0.5, new SphereObstacle(Vector3d.Zero, 1).SignedDistance(new Vector3d(0, 0.5, 0), out _), 15);
        var capsule = new CapsuleObstacle(new Vector3d(0, 0, 0), new Vector3d(2, 0, 0), 0.5);
        Assert.Equal(0.5, capsule.SignedDistance(new Vector3d(1, 1, 0), out var n1), 15);
        Assert.Equal(new Vector3d(0, 1, 0), n1);
        Assert.Equal(Math.Sqrt(2) - 0.5, capsule.SignedDistance(new Vector3d(3, 1, 0), out _), 15);
        var box = new BoxObstacle(Vector3d.Zero, new Vector3d(1, 2, 3));
        Assert.Equal(Math.Sqrt(2), box.SignedDistance(new Vector3d(2, 3, 0), out _), 15);
        Assert.Equal(-0.5, box.SignedDistance(new Vector3d(0.5, 0, 0), out var n2), 15);
        Assert.Equal(new Vector3d(1, 0, 0), n2);
        box.SetOrientation(new Vector3d(1, 1, 0), new Vector3d(-1, 1, 0));
        Assert.Equal(1.0, box.SignedDistance(new Vector3d(Math.Sqrt(2), Math.Sqrt(2), 0), out _), 12);
    }

    [Fact]
    public void A_box_takes_any_finite_axes_that_are_not_parallel_however_short_or_long()
    {
        // Issue 27, item 11: the parallel test multiplied by |axisY|, which underflows to 0 at 1e-200 and overflows to
        // infinity at 3e200, so both were called parallel to (1, 0, 0).
        var box = new BoxObstacle(Vector3d.Zero, new Vector3d(1, 2, 3));
        var cases = new (Vector3d X, Vector3d Y, Vector3d ExpectedY)[]
        {
            (new Vector3d(1, 0, 0), new Vector3d(0, 1e-200, 0), new Vector3d(0, 1, 0)),
            (new Vector3d(1, 0, 0), new Vector3d(0, 3e200, 0), new Vector3d(0, 1, 0)),
            (new Vector3d(1, 0, 0), new Vector3d(5e-324, 5e-324, 0), new Vector3d(0, 1, 0)),
            (new Vector3d(1, 0, 0), new Vector3d(1.7e308, -1.7e308, 0), new Vector3d(0, -1, 0)),
            (new Vector3d(0, 0, 1e-300), new Vector3d(0, 1e300, 1e300), new Vector3d(0, 1, 0)),
        };
        foreach (var (x, y, expectedY) in cases)
        {
            box.SetOrientation(x, y);
            Assert.Equal(expectedY, box.AxisY);
            Assert.Equal(Vector3d.Cross(box.AxisX, box.AxisY), box.AxisZ);
        }

        // Parallel axes are still refused, whatever their lengths, and nothing changes.
        foreach (var y in new[] { new Vector3d(1e-200, 0, 0), new Vector3d(-3e200, 0, 0), new Vector3d(1, 1e-13, 0) })
        {
            Assert.Equal("axisY", Assert.Throws<ArgumentOutOfRangeException>(() => box.SetOrientation(new Vector3d(1, 0, 0), y)).ParamName);
            Assert.Equal(new Vector3d(0, 1, 0), box.AxisY);
        }
    }

    [Theory]
    [InlineData("explicit-euler")]
    [InlineData("semi-implicit-euler")]
    [InlineData("implicit-euler")]
    [InlineData("rk4")]
    [InlineData("velocity-verlet")]
    [InlineData("rk45")]
    [InlineData("xpbd")]
    public void A_particle_at_1000_m_per_s_never_crosses_a_thin_plane_or_box(string integrator)
    {
        // A wall 2 mm thick, a plane, and a particle that moves 16.7 m per step at 60 Hz, at several angles.
        foreach (var angle in new[] { 0.0, 30.0, 60.0, 85.0 })
        {
            var a = angle * Math.PI / 180;
            var direction = new Vector3d(Math.Cos(a), Math.Sin(a), 0);
            foreach (var wall in new Obstacle[]
            {
                new BoxObstacle(new Vector3d(10, 0, 0), new Vector3d(0.001, 1e3, 1e3), 0.5),
                new PlaneObstacle(new Vector3d(10, 0, 0), new Vector3d(-1, 0, 0), 0.5),
            })
            {
                var world = new ParticleWorld();
                world.AddParticle(Vector3d.Zero, 1000 * direction, 1);
                world.AddForce(Gravity.Down(9.81));
                var contacts = new ContactSet();
                contacts.Add(wall);
                world.AddConstraints(contacts);
                var stepper = IntegratorCatalog.Create(integrator);
                for (var step = 0; step < 30; step++)
                {
                    world.Step(stepper, 1.0 / 60.0);
                    Assert.True(world.GetPosition(0).X <= 10 - 0.001 + 1e-6 || wall is PlaneObstacle && world.GetPosition(0).X <= 10 + 1e-6,
                        $"{integrator}, {angle} degrees, {wall.GetType().Name}: crossed to {world.GetPosition(0)} at step {step}");
                }

                Assert.True(world.GetVelocity(0).X < 0, $"{integrator}, {angle} degrees: did not bounce back");
            }
        }
    }

    [Theory]
    [MemberData(nameof(Shapes))]
    public void No_particle_ends_a_step_inside_a_collider_by_more_than_1e_6_m(string kind)
    {
        // A rain of particles of several radii onto the obstacle, moving sideways at the same time; checked at every step.
        var obstacle = Make(kind);
        obstacle.Friction = 0.3;
        obstacle.Restitution = 0.4;
        var world = new ParticleWorld();
        var state = 777u;
        for (var i = 0; i < 60; i++)
        {
            var p = new Vector3d(Next(ref state) * 1.5, 3 + (2 * Math.Abs(Next(ref state))), Next(ref state) * 1.5);
            world.AddParticle(p, new Vector3d(Next(ref state) * 3, -5 * Math.Abs(Next(ref state)), Next(ref state) * 3), 1);
            world.SetRadius(i, 0.02 + (0.05 * Math.Abs(Next(ref state))));
        }

        world.AddForce(Gravity.Down(9.81));
        var contacts = new ContactSet();
        contacts.Add(obstacle);
        world.AddConstraints(contacts);
        foreach (var integrator in new[] { "rk4", "semi-implicit-euler", "xpbd" })
        {
            var stepper = IntegratorCatalog.Create(integrator);
            for (var step = 0; step < 200; step++)
            {
                world.Step(stepper, 1.0 / 60.0);
                for (var i = 0; i < world.Count; i++)
                {
                    var gap = obstacle.SignedDistance(world.GetPosition(i), out _) - world.GetRadius(i);
                    Assert.True(gap >= -1e-6, $"{kind}, {integrator}: particle {i} inside by {-gap} at step {step}");
                }
            }
        }
    }

    [Fact]
    public void A_moving_obstacle_hits_a_resting_particle_with_its_velocity()
    {
        // A piston (a plane moving up at 2 m/s) meets a particle at rest in free space (no gravity): with e = 1 the
        // particle leaves at 2 V = 4 m/s, and the impact is at the time the piston reaches it.
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(0, 1, 0), 1);
        world.SetRadius(0, 0.1);
        var piston = new PlaneObstacle(Vector3d.Zero, new Vector3d(0, 1, 0), restitution: 1) { Velocity = new Vector3d(0, 2, 0) };
        var contacts = new ContactSet();
        contacts.Add(piston);
        world.AddConstraints(contacts);
        FrictionTests.StepFor(world, "rk4", 0.01, 1.0);
        Assert.Equal(4.0, world.GetVelocity(0).Y, 12);
        Assert.Equal(1.0 + (4.0 * (1.0 - 0.45)), world.GetPosition(0).Y, 12); // hit at t = 0.45 s, at y = 1
        Assert.Equal(new Vector3d(0, 2, 0), piston.ShapeAt(1.0).Center);
        Assert.Equal(Vector3d.Zero, piston.Point);
    }

    [Fact]
    public void A_moving_sphere_pushes_a_resting_particle_along_and_rebase_keeps_its_place()
    {
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(1, 0, 0), 1);
        var ball = new SphereObstacle(Vector3d.Zero, 0.5) { Velocity = new Vector3d(1, 0, 0) };
        var contacts = new ContactSet();
        contacts.Add(ball);
        world.AddConstraints(contacts);
        FrictionTests.StepFor(world, "rk4", 0.01, 1.0);
        Assert.Equal(1.0, world.GetVelocity(0).X, 12); // e = 0: it moves with the sphere
        Assert.Equal(1.5, world.GetPosition(0).X, 12);
        ball.Rebase(1.0);
        Assert.Equal(new Vector3d(1, 0, 0), ball.Center);
        Assert.Equal(1.0, ball.ReferenceTime);
        Assert.Equal(ball.Shape.Center, ball.ShapeAt(1.0).Center);
    }

    [Fact]
    public void Shapes_describe_themselves_for_renderers()
    {
        var plane = new PlaneObstacle(new Vector3d(1, 2, 3), new Vector3d(0, 0, 2)).Shape;
        Assert.Equal(ObstacleKind.Plane, plane.Kind);
        Assert.Equal(new Vector3d(0, 0, 1), plane.AxisY);
        Assert.Equal(0.0, Vector3d.Dot(plane.AxisX, plane.AxisY), 15);
        Assert.Equal(plane.AxisZ, Vector3d.Cross(plane.AxisX, plane.AxisY));
        var capsule = new CapsuleObstacle(new Vector3d(0, 0, 0), new Vector3d(0, 0, 4), 0.5).Shape;
        Assert.Equal((ObstacleKind.Capsule, new Vector3d(0, 0, 2), new Vector3d(0, 0, 1), 2.0, 0.5),
            (capsule.Kind, capsule.Center, capsule.AxisY, capsule.HalfExtents.Y, capsule.Radius));
        var box = new BoxObstacle(new Vector3d(1, 1, 1), new Vector3d(1, 2, 3));
        box.SetOrientation(new Vector3d(0, 1, 0), new Vector3d(1, 0, 0));
        Assert.Equal(new Vector3d(0, 0, -1), box.Shape.AxisZ);
        Assert.Equal(ObstacleKind.Sphere, new SphereObstacle(Vector3d.Zero, 2).Shape.Kind);
        Assert.Equal(2.0, new SphereObstacle(Vector3d.Zero, 2).Shape.Radius);
    }

    internal static Obstacle Make(string kind) => kind switch
    {
        "plane" => new PlaneObstacle(new Vector3d(0, 0.5, 0), new Vector3d(0.2, 1, -0.1)),
        "sphere" => new SphereObstacle(new Vector3d(0.1, 0.4, -0.2), 0.8),
        "capsule" => new CapsuleObstacle(new Vector3d(-1, 0.5, 0), new Vector3d(1, 0.7, 0.3), 0.4),
        _ => Box(),
    };

    private static BoxObstacle Box()
    {
        var box = new BoxObstacle(new Vector3d(0, 0.5, 0), new Vector3d(1, 0.3, 0.6));
        box.SetOrientation(new Vector3d(1, 0.3, 0), new Vector3d(0, 1, 0.2));
        return box;
    }

    /// <summary>A number in [-1, 1) from a xorshift generator.</summary>
    internal static double Next(ref uint state)
    {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        return (state / 2147483648.0) - 1.0;
    }
}
