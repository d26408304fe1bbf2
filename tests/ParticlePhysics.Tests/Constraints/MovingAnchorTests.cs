using System;
using ParticlePhysics.Constraints;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Constraints;

/// <summary>
/// Anchors the host moves: a pinned particle has the velocity of its path, springs and dampers see it, and a released
/// particle keeps it; particles attached to a moving body follow it.
/// </summary>
public class MovingAnchorTests
{
    private const double Speed = 0.5;
    private const double Stiffness = 20;
    private const double Damping = 1; // c / k = 0.05: a damper that saw the anchor at rest would hold 2.5 cm off

    [Theory]
    [InlineData("rk4")]
    [InlineData("implicit-euler")]
    [InlineData("velocity-verlet")]
    [InlineData("xpbd")]
    public void A_damped_spring_pulled_at_constant_speed_settles_at_exactly_its_rest_length(string integrator)
    {
        var world = PulledSpring(out var springs);
        world.Pin(0, new Vector3d(Speed, 0, 0));
        var stepper = IntegratorCatalog.Create(integrator);
        StateMetrics.Run(world, stepper, 0.002, 30000); // 60 s: the start's transient decays as e^(-c t / 2 m)
        // xpbd settles 2.2e-9 m off: its velocities are differences of positions 30 m from the origin over substeps
        // of 0.2 ms, quantised to 1.8e-11 m/s, which the spring's projection balances with that stretch.
        var stretch = (world.GetPosition(0) - world.GetPosition(1)).Length - springs.GetRestLength(0);
        var bound = integrator == "xpbd" ? 1e-8 : 1e-9;
        Assert.True(Math.Abs(stretch) < bound, $"{integrator}: {stretch:E3} m off the rest length");
        Assert.Equal(Speed, world.GetVelocity(1).X, 1e-9);
        Assert.Equal(60 * Speed, world.GetPosition(0).X, 1e-9);
    }

    [Fact]
    public void The_host_driving_the_anchor_along_its_path_gives_the_same_rest_length()
    {
        // Each frame the host names where the anchor will be; the world takes the velocity from that path.
        var world = PulledSpring(out var springs);
        world.Pin(0);
        var rk4 = new RungeKutta4();
        const double frame = 1.0 / 60;
        for (var f = 1; f <= 3600; f++)
        {
            world.MoveKinematic(0, new Vector3d(Speed * f * frame, 0, 0), frame);
            world.Step(rk4, frame);
        }

        var stretch = (world.GetPosition(0) - world.GetPosition(1)).Length - springs.GetRestLength(0);
        Assert.True(Math.Abs(stretch) < 1e-9, $"{stretch:E3} m off");
        Assert.Equal(Speed * 60, world.GetPosition(0).X, 1e-9);
    }

    [Fact]
    public void Moving_the_anchor_by_its_position_alone_leaves_the_damper_c_v_over_k_off()
    {
        // The old way, and why anchors have velocities now: the damper sees the anchor at rest and drags the mass.
        var world = PulledSpring(out var springs);
        world.Pin(0);
        var rk4 = new RungeKutta4();
        for (var s = 1; s <= 30000; s++)
        {
            world.SetPosition(0, new Vector3d(Speed * s * 0.002, 0, 0));
            world.Step(rk4, 0.002);
        }

        // c v / k = 2.5 cm, less the anchor's lead of one step (v dt = 1 mm) that the spring sees.
        var stretch = (world.GetPosition(0) - world.GetPosition(1)).Length - springs.GetRestLength(0);
        Assert.Equal(Damping * Speed / Stiffness, stretch, 1e-3);
    }

    [Theory]
    [InlineData("explicit-euler")]
    [InlineData("rk4")]
    [InlineData("rk45")]
    [InlineData("xpbd")]
    public void A_released_particle_keeps_the_anchors_velocity(string integrator)
    {
        var world = new ParticleWorld();
        world.AddParticle(Vector3d.Zero, 2);
        world.AddForce(new Gravity());
        world.Pin(0, new Vector3d(1, 2, 0));
        var stepper = IntegratorCatalog.Create(integrator);
        StateMetrics.Run(world, stepper, 0.01, 50);
        Assert.Equal(new Vector3d(1, 2, 0), world.GetVelocity(0));
        Assert.Equal(0.5, world.GetPosition(0).X, 1e-12);
        Assert.Equal(1.0, world.GetPosition(0).Y, 1e-12);

        world.Unpin(0);
        Assert.Equal(new Vector3d(1, 2, 0), world.GetVelocity(0));
        StateMetrics.Run(world, stepper, 0.01, 10);
        Assert.Equal(1, world.GetVelocity(0).X, 1e-12);
        Assert.Equal(2 - (9.81 * 0.1), world.GetVelocity(0).Y, 1e-9);
    }

    [Fact]
    public void A_pinned_particle_keeps_exactly_the_velocity_it_is_given_and_a_fixed_pin_never_moves()
    {
        foreach (var name in IntegratorCatalog.Names)
        {
            var world = new ClothScenario().Build();
            world.SetVelocity(0, new Vector3d(0.25, -0.5, 0));
            var start = world.GetPosition(10);
            StateMetrics.Run(world, IntegratorCatalog.Create(name), 0.001, 100);
            Assert.Equal(new Vector3d(0.25, -0.5, 0), world.GetVelocity(0));
            Assert.Equal(start, world.GetPosition(10));
            Assert.Equal(Vector3d.Zero, world.GetVelocity(10));
            Assert.Equal(0.025, world.GetPosition(0).X, 1e-12);
        }
    }

    [Fact]
    public void Particles_attached_to_a_rotating_body_reach_their_points_every_frame_and_fly_on_when_detached()
    {
        var world = new ParticleWorld();
        var first = world.AddParticle(new Vector3d(1, 0, 0), 1);
        var second = world.AddParticle(new Vector3d(0, 2, 0), 1);
        world.AddForce(new Gravity());
        var body = new KinematicBody(world, Vector3d.Zero, Rotation3d.Identity);
        body.Attach(first);
        body.Attach(second);
        Assert.True(world.IsPinned(first));
        Assert.Throws<ArgumentException>(() => body.Attach(first));

        // A quarter turn a second about z, while the body drifts along x at 0.3 m/s.
        var rk4 = new RungeKutta4();
        const double frame = 1.0 / 60;
        for (var f = 1; f <= 60; f++)
        {
            var pose = Rotation3d.FromAxisAngle(new Vector3d(0, 0, 1), 0.5 * Math.PI * f * frame);
            body.MoveTo(new Vector3d(0.3 * f * frame, 0, 0), pose, frame);
            world.Step(rk4, frame);
            var expected = body.PointAt(new Vector3d(1, 0, 0));
            Assert.True((world.GetPosition(first) - expected).Length < 1e-12, $"frame {f}: {world.GetPosition(first)} vs {expected}");
        }

        Assert.Equal(0.3, world.GetPosition(first).X, 1e-12);
        Assert.Equal(1.0, world.GetPosition(first).Y, 1e-12);
        Assert.Equal(-2.0, world.GetPosition(second).X - 0.3, 1e-12);

        // Detached, it keeps the velocity of the body's point over the last frame and falls from there.
        var velocity = world.GetVelocity(second);
        Assert.True(velocity.Length > 1, $"{velocity}");
        Assert.True(body.Detach(second));
        Assert.False(body.Detach(second));
        Assert.False(world.IsPinned(second));
        Assert.Equal(velocity, world.GetVelocity(second));
        world.Step(rk4, 0.1);
        Assert.Equal(velocity.X, world.GetVelocity(second).X, 1e-12);
        Assert.Equal(velocity.Y - 0.981, world.GetVelocity(second).Y, 1e-12);
    }

    [Fact]
    public void Rotations_turn_vectors_as_their_axis_and_angle_say()
    {
        var quarter = Rotation3d.FromAxisAngle(new Vector3d(0, 0, 2), Math.PI / 2);
        var turned = quarter.Rotate(new Vector3d(1, 0, 0));
        Assert.Equal(0, turned.X, 1e-15);
        Assert.Equal(1, turned.Y, 1e-15);
        var back = quarter.Inverse().Rotate(turned);
        Assert.Equal(1, back.X, 1e-15);
        Assert.Equal(new Vector3d(1, 2, 3), default(Rotation3d).Rotate(new Vector3d(1, 2, 3)));
        Assert.Equal(1, new Rotation3d(0, 0, 0, 5).W);
        Assert.Throws<ArgumentException>(() => new Rotation3d(0, 0, 0, 0));
        Assert.Throws<ArgumentException>(() => Rotation3d.FromAxisAngle(Vector3d.Zero, 1));
    }

    [Fact]
    public void State_vectors_may_give_pinned_particles_a_velocity()
    {
        var world = new ParticleWorld();
        world.AddParticle(Vector3d.Zero, 1);
        world.Pin(0);
        world.SetState(new double[] { 0, 0, 0, 3, 0, 0 });
        world.Step(new RungeKutta4(), 0.5);
        Assert.Equal(1.5, world.GetPosition(0).X, 1e-15);
        Assert.True(world.IsPinned(0));
    }

    /// <summary>Particle 0 (the anchor) at the origin, particle 1 a rest length behind it, a damped spring between.</summary>
    private static ParticleWorld PulledSpring(out SpringNetwork springs)
    {
        var world = new ParticleWorld();
        world.AddParticle(Vector3d.Zero, 1);
        world.AddParticle(new Vector3d(-1, 0, 0), 1);
        springs = new SpringNetwork(world);
        springs.Add(0, 1, Stiffness, 1, Damping);
        world.AddForce(springs);
        world.AddConstraints(new SpringProjection(springs));
        return world;
    }
}
