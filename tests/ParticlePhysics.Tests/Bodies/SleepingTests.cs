using System;
using ParticlePhysics.Bodies;
using ParticlePhysics.Constraints;
using ParticlePhysics.Contacts;
using ParticlePhysics.Driver;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Parallel;
using Xunit;

namespace ParticlePhysics.Tests.Bodies;

/// <summary>
/// Sleeping (<see cref="ParticleWorld.SleepSpeed"/>): islands that stay slow stop moving; an impact, a moving collider,
/// a change by the host or to a force wakes them in the same step; a failed step or frame leaves sleep as it was.
/// </summary>
public class SleepingTests
{
    private const double Dt = 1.0 / 60;
    private readonly Xunit.Abstractions.ITestOutputHelper _output;

    public SleepingTests(Xunit.Abstractions.ITestOutputHelper output)
    {
        _output = output;
    }

    [Fact]
    public void A_box_at_rest_falls_asleep_after_the_sleep_time_and_then_does_not_move_a_bit()
    {
        var (world, bodies, _) = BoxOnGround();
        var xpbd = new Xpbd(10);
        var asleepAt = -1;
        for (var step = 0; step < 180 && asleepAt < 0; step++)
        {
            world.Step(xpbd, Dt);
            asleepAt = world.SleepingCount == world.Count ? step : -1;
        }

        _output.WriteLine($"the box fell asleep at step {asleepAt} ({(asleepAt + 1) * Dt:F3} s)");
        Assert.True(asleepAt >= 30, $"asleep after {asleepAt + 1} steps, before the sleep time of 0.5 s had passed");
        Assert.True(asleepAt > 0, "the box never fell asleep");
        var positions = world.Positions.ToArray();
        for (var step = 0; step < 60; step++)
        {
            world.Step(xpbd, Dt);
        }

        Assert.Equal(positions, world.Positions.ToArray());
        Assert.Equal(0.0, world.KineticEnergy());
        Assert.All(world.InverseMasses.ToArray(), w => Assert.Equal(0.0, w));
        Assert.Equal(Vector3d.Zero, bodies.GetPose(0).LinearVelocity);
    }

    [Fact]
    public void Without_sleep_speed_or_with_a_generator_that_cannot_tell_its_links_nothing_sleeps()
    {
        var (world, _, _) = BoxOnGround(sleepSpeed: 0.0);
        var xpbd = new Xpbd(10);
        for (var step = 0; step < 90; step++)
        {
            world.Step(xpbd, Dt);
        }

        Assert.Equal(0, world.SleepingCount);

        var (other, _, _) = BoxOnGround();
        other.AddForce(new SpringNetwork(other));
        for (var step = 0; step < 90; step++)
        {
            other.Step(xpbd, Dt);
        }

        Assert.Equal(0, other.SleepingCount);
    }

    [Fact]
    public void A_ball_dropped_on_a_sleeping_box_wakes_it_in_the_step_of_the_impact_and_pushes_it()
    {
        var (world, bodies, _) = BoxOnGround();
        var xpbd = new Xpbd(10);
        for (var step = 0; step < 60; step++)
        {
            world.Step(xpbd, Dt);
        }

        Assert.Equal(world.Count, world.SleepingCount);
        var top = 0.0;
        for (var i = 0; i < world.Count; i++)
        {
            top = Math.Max(top, world.GetPosition(i).Y + world.GetRadius(i));
        }

        // A heavy ball falling at 3 m/s, 2 cm above the box's top: it reaches the box within the next step.
        var ball = world.AddParticle(new Vector3d(0.05, top + 0.05 + 0.02, 0.05), new Vector3d(0, -3, 0), 5.0);
        world.SetRadius(ball, 0.05);
        var box = world.Count - 1;
        var touched = -1;
        for (var step = 0; step < 10 && touched < 0; step++)
        {
            world.Step(xpbd, Dt);
            var gap = double.PositiveInfinity;
            for (var i = 0; i < box; i++)
            {
                gap = Math.Min(gap, (world.GetPosition(i) - world.GetPosition(ball)).Length - world.GetRadius(i) - 0.05);
            }

            if (gap < 0.01)
            {
                touched = step;
                Assert.False(world.IsAsleep(0), "the box still sleeps in the step the ball reached it");
                Assert.True(bodies.GetPose(0).LinearVelocity.Y < -0.05, $"the box did not take the impact: v = {bodies.GetPose(0).LinearVelocity}");
            }
        }

        Assert.True(touched >= 0, "the ball never reached the box");

        // Falling asleep again, and another wake, allocate nothing once the world has stepped.
        var before = GC.GetAllocatedBytesForCurrentThread();
        for (var step = 0; step < 90; step++)
        {
            world.Step(xpbd, Dt);
        }

        Assert.True(world.SleepingCount > 0, "nothing fell asleep again");
        world.SetVelocity(ball, new Vector3d(0, 2, 0));
        for (var step = 0; step < 30; step++)
        {
            world.Step(xpbd, Dt);
        }

        Assert.Equal(0, GC.GetAllocatedBytesForCurrentThread() - before);
    }

    [Fact]
    public void A_box_asleep_on_one_knocked_away_wakes_and_falls_instead_of_floating()
    {
        var (world, bodies, contacts) = BoxOnGround();
        RigidContactTests.AddBox(world, bodies, new Vector3d(0.05, 0.3, 0.05), new Vector3d(0.2, 0.2, 0.2), Rotation3d.Identity, 1.0);

        // A wall beside the lower box, lower than it, still while they fall asleep (adding it later would wake all).
        var wall = new BoxObstacle(new Vector3d(-0.2, 0.09, 0.05), new Vector3d(0.1, 0.09, 0.5));
        contacts.Add(wall);
        var xpbd = new Xpbd(10);
        for (var step = 0; step < 90 && world.SleepingCount < world.Count; step++)
        {
            world.Step(xpbd, Dt);
        }

        Assert.Equal(world.Count, world.SleepingCount);

        // Driven at 2 m/s along x, it pushes the lower box out: nothing approaches the upper box, but its support moves
        // away, and it must not stay in the air.
        wall.ReferenceTime = world.Time;
        wall.Velocity = new Vector3d(2, 0, 0);
        for (var step = 0; step < 60; step++)
        {
            world.Step(xpbd, Dt);
        }

        var lower = bodies.GetPose(0).Position;
        var upper = bodies.GetPose(1).Position;
        _output.WriteLine($"after 1 s: lower box at {lower}, upper box at {upper}");
        Assert.True(lower.X > 0.3, $"the lower box was not knocked away: {lower}");
        Assert.True(upper.Y < 0.15, $"the upper box did not fall when its support left: {upper}");
    }

    [Fact]
    public void A_resting_particle_on_a_sleeping_box_does_not_wake_it_and_then_sleeps_with_it()
    {
        var (world, _, _) = BoxOnGround();
        var xpbd = new Xpbd(10);
        for (var step = 0; step < 60; step++)
        {
            world.Step(xpbd, Dt);
        }

        // Laid on the box at rest, a few micrometres above it.
        var top = 0.0;
        for (var i = 0; i < world.Count; i++)
        {
            top = Math.Max(top, world.GetPosition(i).Y + world.GetRadius(i));
        }

        var pebble = world.AddParticle(new Vector3d(0.05, top + 0.02 + 1e-6, 0.05), 0.01);
        world.SetRadius(pebble, 0.02);
        var boxAwake = 0;
        for (var step = 0; step < 60; step++)
        {
            world.Step(xpbd, Dt);
            boxAwake += world.IsAsleep(0) ? 0 : 1;
        }

        Assert.Equal(0, boxAwake);
        Assert.True(world.IsAsleep(pebble), "the pebble at rest on the sleeping box did not fall asleep");
    }

    [Fact]
    public void The_host_and_the_forces_wake_what_they_change()
    {
        var (world, _, contacts) = BoxOnGround();
        var xpbd = new Xpbd(10);
        var gravity = (Gravity)world.Forces[0];
        void Sleep()
        {
            for (var step = 0; step < 60 && world.SleepingCount < world.Count; step++)
            {
                world.Step(xpbd, Dt);
            }

            Assert.Equal(world.Count, world.SleepingCount);
        }

        Sleep();
        world.SetVelocity(3, new Vector3d(0.5, 0, 0));
        Assert.Equal(0, world.SleepingCount); // the whole body, through its island
        Assert.NotEqual(0.0, world.InverseMasses[0]);
        Sleep();
        gravity.Acceleration = new Vector3d(2, -9.81, 0); // tilted: the box must slide off
        world.Step(xpbd, Dt);
        Assert.Equal(0, world.SleepingCount);
        gravity.Acceleration = new Vector3d(0, -9.81, 0);
        Sleep();
        contacts.ParticleFriction = 0.1;
        world.Step(xpbd, Dt);
        Assert.True(world.SleepingCount < world.Count, "a change of friction left the box asleep");
        Sleep();
        world.Wake(0);
        Assert.Equal(0, world.SleepingCount);
        Sleep();
        world.SetState(world.State.ToArray());
        Assert.Equal(0, world.SleepingCount);
    }

    [Fact]
    public void A_collider_driven_into_a_sleeping_box_wakes_it_and_pushes_it()
    {
        var (world, bodies, contacts) = BoxOnGround();
        var xpbd = new Xpbd(10);
        for (var step = 0; step < 60; step++)
        {
            world.Step(xpbd, Dt);
        }

        Assert.Equal(world.Count, world.SleepingCount);
        var pusher = new SphereObstacle(new Vector3d(-0.2, 0.1, 0.05), 0.1) { Velocity = new Vector3d(1, 0, 0), ReferenceTime = world.Time };
        contacts.Add(pusher);
        for (var step = 0; step < 12; step++)
        {
            world.Step(xpbd, Dt);
        }

        Assert.True(bodies.GetPose(0).Position.X > 0.05 + 0.02, $"the box was not pushed: centre at {bodies.GetPose(0).Position}");
    }

    [Fact]
    public void A_failed_step_and_a_failed_frame_leave_sleep_as_it_was()
    {
        var (world, _, _) = BoxOnGround();
        var xpbd = new Xpbd(10);
        for (var step = 0; step < 60; step++)
        {
            world.Step(xpbd, Dt);
        }

        Assert.Equal(world.Count, world.SleepingCount);

        // A pinned ball driven at 60 m/s into the box, beyond a divergence limit of 50 m/s: the step wakes the box at
        // the impact, then is refused, and the box sleeps again with the state as it was.
        world.DivergenceLimit = 50;
        var ball = world.AddParticle(new Vector3d(0.05, 0.3, 0.05), 1.0);
        world.SetRadius(ball, 0.05);
        world.Pin(ball, new Vector3d(0, -60, 0));
        var sleepingBefore = world.SleepingCount;
        var before = world.State.ToArray();
        Assert.Throws<SimulationDivergedException>(() => world.Step(xpbd, Dt));
        Assert.Equal(sleepingBefore, world.SleepingCount);
        Assert.True(world.IsAsleep(0));
        Assert.Equal(0.0, world.InverseMasses[0]);
        Assert.Equal(before, world.State.ToArray());

        var driver = new FixedTimestepDriver(world, xpbd, Dt);
        Assert.Throws<SimulationDivergedException>(() => driver.Advance(Dt));
        Assert.Equal(sleepingBefore, world.SleepingCount);
        Assert.True(world.IsAsleep(0));
    }

    [Fact]
    public void A_world_after_a_failed_frame_steps_on_bit_for_bit_as_one_that_never_tried_it()
    {
        ParticleWorld Make(bool fail)
        {
            var (world, _, _) = BoxOnGround();
            var xpbd = new Xpbd(10);
            var driver = new FixedTimestepDriver(world, xpbd, Dt);
            for (var frame = 0; frame < 40; frame++)
            {
                driver.Advance(Dt); // calm from the start: the box falls asleep after 31 steps
            }

            Assert.Equal(world.Count, world.SleepingCount);
            // A pinned ball driven at 60 m/s into the box, beyond the divergence limit: the frame fails after waking it.
            world.DivergenceLimit = 50;
            var ball = world.AddParticle(new Vector3d(0.05, 0.3, 0.05), 1.0);
            world.SetRadius(ball, 0.05);
            driver = new FixedTimestepDriver(world, xpbd, Dt);
            if (fail)
            {
                world.Pin(ball, new Vector3d(0, -60, 0));
                Assert.Throws<SimulationDivergedException>(() => driver.Advance(Dt));
            }

            world.Pin(ball, new Vector3d(0, -0.5, 0));
            for (var frame = 0; frame < 60; frame++)
            {
                driver.Advance(Dt);
            }

            return world;
        }

        var failed = Make(fail: true);
        var clean = Make(fail: false);
        Assert.Equal(clean.State.ToArray(), failed.State.ToArray());
        Assert.Equal(clean.SleepingCount, failed.SleepingCount);
    }

    [Fact]
    public void A_sleeping_pile_keeps_the_same_bits_on_one_core_or_two()
    {
        var one = Pile(null);
        using var runner = new WorkerThreadRunner(2);
        var two = Pile(runner);
        Assert.Equal(one.Sleeping, two.Sleeping);
        Assert.Equal(one.State, two.State);
        _output.WriteLine($"{one.Sleeping} of 300 particles asleep after 4 s");
        Assert.True(one.Sleeping > 0, "nothing fell asleep");
    }

    [Fact]
    public void Bad_settings_are_refused_with_the_value_and_what_is_allowed()
    {
        var world = new ParticleWorld();
        Assert.Contains(">= 0 m/s", Assert.Throws<ArgumentOutOfRangeException>(() => world.SleepSpeed = -1).Message);
        Assert.Contains("NaN", Assert.Throws<ArgumentOutOfRangeException>(() => world.SleepSpeed = double.NaN).Message);
        Assert.Contains("> 0 s", Assert.Throws<ArgumentOutOfRangeException>(() => world.SleepTime = 0).Message);
        Assert.Equal(0.0, world.SleepSpeed);
        Assert.Equal(ParticleWorld.DefaultSleepTime, world.SleepTime);
    }

    private static (ParticleWorld World, ShapeMatching Bodies, ContactSet Contacts) BoxOnGround(double sleepSpeed = 0.05)
    {
        var world = new ParticleWorld { SleepSpeed = sleepSpeed };
        var bodies = new ShapeMatching(world);
        RigidContactTests.AddBox(world, bodies, new Vector3d(0.05, 0.1, 0.05), new Vector3d(0.2, 0.2, 0.2), Rotation3d.Identity, 1.0);
        world.AddForce(Gravity.Down(9.81));
        var contacts = new ContactSet { ParticleCollisions = true, ParticleFriction = 0.5, PairFilter = bodies.PairFilter };
        contacts.Add(PlaneObstacle.Ground(0, 0.5));
        world.AddConstraints(bodies);
        world.AddConstraints(contacts);
        return (world, bodies, contacts);
    }

    private static (int Sleeping, double[] State) Pile(IParallelRunner? runner)
    {
        var world = new ParticleWorld { SleepSpeed = 0.05, Runner = runner };
        world.AddForce(Gravity.Down(9.81));
        for (var i = 0; i < 300; i++)
        {
            // A column of grains on a jittered lattice, 5 x 5 wide.
            var p = world.AddParticle(new Vector3d((0.021 * (i % 5)) + (0.001 * (i % 3)), 0.011 + (0.021 * (i / 25)), 0.021 * ((i / 5) % 5)), 0.004);
            world.SetRadius(p, 0.01);
        }

        var contacts = new ContactSet { ParticleCollisions = true };
        contacts.SetGranular(0, 300, 0.6, 0.3);
        contacts.Add(PlaneObstacle.Ground(0, 1.0));
        world.AddConstraints(contacts);
        var xpbd = new Xpbd(10);
        for (var step = 0; step < 240; step++)
        {
            world.Step(xpbd, Dt);
        }

        return (world.SleepingCount, world.State.ToArray());
    }
}
