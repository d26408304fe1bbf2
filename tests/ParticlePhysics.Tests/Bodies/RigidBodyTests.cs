using System;
using ParticlePhysics.Bodies;
using ParticlePhysics.Constraints;
using ParticlePhysics.Contacts;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using Xunit;

namespace ParticlePhysics.Tests.Bodies;

/// <summary>
/// Rigid bodies by shape matching against Euler's equations of a free rigid body: angular momentum, the stable major
/// axis, the Dzhanibekov flip about the intermediate axis at the time an independent RK4 gives.
/// </summary>
public class RigidBodyTests
{
    private readonly Xunit.Abstractions.ITestOutputHelper _output;

    public RigidBodyTests(Xunit.Abstractions.ITestOutputHelper output)
    {
        _output = output;
    }

    private static readonly Vector3d _boxSize = new(0.8, 0.4, 0.2); // 8 x 4 x 2 particles

    /// <summary>A world with one rigid box of <paramref name="size"/> at spacing 0.1 m, its frame the world's.</summary>
    internal static (ParticleWorld World, ShapeMatching Bodies) Box(Vector3d size, double totalMass = 1.0, Vector3d? center = null)
    {
        var world = new ParticleWorld();
        var bodies = new ShapeMatching(world);
        RigidContactTests.AddBox(world, bodies, center ?? Vector3d.Zero, size, Rotation3d.Identity, totalMass);
        world.AddConstraints(bodies);
        return (world, bodies);
    }

    [Fact]
    public void A_box_spun_about_its_major_axis_keeps_its_angular_momentum_axis_and_shape_for_12_s()
    {
        var (world, bodies) = Box(_boxSize);
        world.AddForce(Gravity.Down(9.81));
        bodies.SetMotion(0, new Vector3d(1, 2, 0), new Vector3d(0, 0, 3)); // z: the major axis of an 8 x 4 x 2 box
        var l0 = AngularMomentum(world);
        var xpbd = new Xpbd(10);
        var worst = 0.0;
        var worstAxis = 0.0;
        var worstShape = 0.0;
        for (var step = 0; step < 12 * 120; step++)
        {
            world.Step(xpbd, 1.0 / 120);
            var l = AngularMomentum(world);
            worst = Math.Max(worst, Math.Abs(l.Length - l0.Length) / l0.Length);
            worstAxis = Math.Max(worstAxis, (l / l.Length - l0 / l0.Length).Length);
            var pose = bodies.GetPose(0);
            worstAxis = Math.Max(worstAxis, (pose.AngularVelocity / pose.AngularVelocity.Length - new Vector3d(0, 0, 1)).Length);
            worstShape = Math.Max(worstShape, ShapeError(world, bodies));
        }

        _output.WriteLine($"|L| drift {worst:E3}, axis {worstAxis:E3}, shape {worstShape:E3} m");
        Assert.True(worst < 1e-3, $"|L| drifted by {worst:E3} of itself");
        Assert.True(worstAxis < 1e-2, $"the spin axis moved by {worstAxis:E3}");
        Assert.True(worstShape < 1e-6 * _boxSize.Length, $"the shape moved by {worstShape:E3} m");
    }

    [Fact]
    public void A_box_spun_about_its_intermediate_axis_flips_when_eulers_equations_say()
    {
        var (world, bodies) = Box(_boxSize);
        var omega0 = new Vector3d(0.01, 3, 0.01);
        bodies.SetMotion(0, Vector3d.Zero, omega0); // the body frame is the world's at the start
        var xpbd = new Xpbd(10);
        var flip = double.NaN;
        for (var step = 1; step <= 20 * 120 && double.IsNaN(flip); step++)
        {
            world.Step(xpbd, 1.0 / 120);
            var pose = bodies.GetPose(0);
            if (pose.Rotation.Inverse().Rotate(pose.AngularVelocity).Y < 0)
            {
                flip = world.Time;
            }
        }

        var expected = EulerFlipTime(PrincipalInertia(world, bodies), omega0);
        _output.WriteLine($"flip at {flip:F4} s, Euler's equations {expected:F4} s");
        Assert.False(double.IsNaN(flip), $"no flip in 20 s; Euler's equations flip at {expected:F3} s");
        Assert.True(Math.Abs(flip - expected) < 0.05 * expected, $"flip at {flip:F3} s; Euler's equations (RK4) give {expected:F3} s");
    }

    [Fact]
    public void A_body_in_free_flight_keeps_its_linear_momentum_and_falls_as_a_point_mass()
    {
        var (world, bodies) = Box(_boxSize);
        world.AddForce(Gravity.Down(9.81));
        bodies.SetMotion(0, new Vector3d(1, 2, 0.5), new Vector3d(1, 2, 3));
        var xpbd = new Xpbd(10);
        for (var step = 0; step < 120; step++)
        {
            world.Step(xpbd, 1.0 / 120);
        }

        // Semi-implicit Euler of the centre of mass in n substeps: y = v t - g h_s^2 n (n + 1) / 2 exactly.
        var pose = bodies.GetPose(0);
        var h = 1.0 / 1200;
        const int n = 1200;
        Assert.Equal(1.0, pose.Position.X, 10);
        Assert.Equal(2.0 - (9.81 * h * h * n * (n + 1) / 2), pose.Position.Y, 10);
        Assert.Equal(2.0 - (9.81 * h * n), pose.LinearVelocity.Y, 10);
        Assert.True(ShapeError(world, bodies) < 1e-9);
    }

    [Fact]
    public void A_box_launched_along_the_ground_stops_after_v0_squared_over_2_mu_g()
    {
        const double mu = 0.4;
        const double v0 = 2.0;
        var (world, bodies) = Box(new Vector3d(0.4, 0.2, 0.4), center: new Vector3d(0, 0.1, 0));
        world.AddForce(Gravity.Down(9.81));
        var contacts = new ContactSet { PairFilter = bodies.PairFilter };
        contacts.Add(PlaneObstacle.Ground(0, mu));
        world.AddConstraints(contacts);
        var xpbd = new Xpbd(10);
        for (var step = 0; step < 30; step++)
        {
            world.Step(xpbd, 1.0 / 60); // settle onto the ground
        }

        var start = bodies.GetPose(0).Position.X;
        bodies.SetMotion(0, new Vector3d(v0, 0, 0), Vector3d.Zero);
        for (var step = 0; step < 120; step++)
        {
            world.Step(xpbd, 1.0 / 60);
        }

        var travelled = bodies.GetPose(0).Position.X - start;
        var expected = v0 * v0 / (2 * mu * 9.81);
        _output.WriteLine($"slid {travelled:F5} m, v0^2 / (2 mu g) = {expected:F5} m");
        Assert.True(Math.Abs(bodies.GetPose(0).LinearVelocity.X) < 1e-6, $"still sliding at {bodies.GetPose(0).LinearVelocity.X} m/s");
        Assert.True(Math.Abs(travelled - expected) < 0.03 * expected, $"slid {travelled:F4} m; v0^2 / (2 mu g) = {expected:F4} m");
    }

    internal static Vector3d AngularMomentum(ParticleWorld world)
    {
        var c = Vector3d.Zero;
        var mass = 0.0;
        for (var i = 0; i < world.Count; i++)
        {
            mass += world.GetMass(i);
            c += world.GetMass(i) * world.GetPosition(i);
        }

        c /= mass;
        var l = Vector3d.Zero;
        for (var i = 0; i < world.Count; i++)
        {
            l += world.GetMass(i) * Vector3d.Cross(world.GetPosition(i) - c, world.GetVelocity(i));
        }

        return l;
    }

    /// <summary>The largest distance of a particle from where the body's pose puts its rest offset.</summary>
    internal static double ShapeError(ParticleWorld world, ShapeMatching bodies)
    {
        var pose = bodies.GetPose(0);
        var worst = 0.0;
        var rest = bodies.RestShapeOf(0);
        var particles = bodies.ParticlesOf(0);
        for (var k = 0; k < particles.Length; k++)
        {
            worst = Math.Max(worst, (world.GetPosition(particles[k]) - (pose.Position + pose.Rotation.Rotate(rest[k]))).Length);
        }

        return worst;
    }

    /// <summary>The lattice's inertia tensor in the body frame: diagonal for a box (its axes are principal).</summary>
    private static Vector3d PrincipalInertia(ParticleWorld world, ShapeMatching bodies)
    {
        double ixx = 0, iyy = 0, izz = 0;
        var rest = bodies.RestShapeOf(0);
        var particles = bodies.ParticlesOf(0);
        for (var k = 0; k < rest.Length; k++)
        {
            var m = world.GetMass(particles[k]);
            var d = rest[k];
            ixx += m * ((d.Y * d.Y) + (d.Z * d.Z));
            iyy += m * ((d.X * d.X) + (d.Z * d.Z));
            izz += m * ((d.X * d.X) + (d.Y * d.Y));
        }

        return new Vector3d(ixx, iyy, izz);
    }

    /// <summary>Euler's equations I w' = (I w) x w by RK4 at 1e-4 s: the first time w_y &lt; 0 (interpolated).</summary>
    private static double EulerFlipTime(Vector3d inertia, Vector3d omega)
    {
        Vector3d Rate(Vector3d w) => new(
            (inertia.Y - inertia.Z) * w.Y * w.Z / inertia.X,
            (inertia.Z - inertia.X) * w.Z * w.X / inertia.Y,
            (inertia.X - inertia.Y) * w.X * w.Y / inertia.Z);
        const double h = 1e-4;
        var w = omega;
        for (var t = 0.0; t < 60; t += h)
        {
            var k1 = Rate(w);
            var k2 = Rate(w + (0.5 * h * k1));
            var k3 = Rate(w + (0.5 * h * k2));
            var k4 = Rate(w + (h * k3));
            var next = w + (h / 6 * (k1 + (2 * k2) + (2 * k3) + k4));
            if (next.Y < 0)
            {
                return t + (h * w.Y / (w.Y - next.Y));
            }

            w = next;
        }

        return double.NaN;
    }
}
