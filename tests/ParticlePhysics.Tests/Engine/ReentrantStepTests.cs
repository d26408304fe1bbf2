using System;
using System.Numerics;
using ParticlePhysics.Constraints;
using ParticlePhysics.Contacts;
using ParticlePhysics.Driver;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Parallel;
using ParticlePhysics.Snapshots;

namespace ParticlePhysics.Tests.Engine;

/// <summary>
/// Issue 27, item 1: a step started from inside the world's own step (by a force, a pair filter or a constraint set)
/// was accepted. It swapped the buffers the outer step was writing into: the time advanced by two steps while a
/// falling ball stayed where it was. Every entry into the world from inside its step is now refused, and the outer
/// step fails whole: the world, its integrator and its driver as they were.
/// </summary>
public class ReentrantStepTests
{
    private const double Dt = 0.01;

    [Theory]
    [InlineData("explicit-euler")]
    [InlineData("semi-implicit-euler")]
    [InlineData("implicit-euler")]
    [InlineData("velocity-verlet")]
    [InlineData("rk4")]
    [InlineData("rk45")]
    [InlineData("xpbd")]
    public void A_step_from_inside_a_force_is_refused_and_the_outer_step_leaves_the_world_as_it_was(string integrator)
    {
        var (world, method) = Ball(integrator);
        var nested = new Reentrant(() => world.Step(method, Dt));
        world.AddForce(nested);
        ExpectRefused(world, nested, () => world.Step(method, Dt));

        // Then, without the nested call, two clean steps: semi-implicit Euler's free fall is 1 - g h^2 (1 + 2).
        nested.Armed = false;
        world.Step(method, Dt);
        world.Step(method, Dt);
        Assert.Equal(2 * Dt, world.Time, 15);
        if (integrator == "semi-implicit-euler")
        {
            Assert.Equal(0.997057, world.GetPosition(0).Y, 12);
        }
    }

    [Fact]
    public void A_step_from_inside_a_pair_filter_is_refused()
    {
        // Two touching spheres falling side by side: the broad phase asks the filter about their pair in every step.
        var (world, method) = Ball("semi-implicit-euler");
        world.AddParticle(new Vector3d(0.15, 1, 0), 1);
        world.SetRadius(0, 0.1);
        world.SetRadius(1, 0.1);
        var filter = new ReentrantFilter(() => world.Step(method, Dt));
        world.AddConstraints(new ContactSet { ParticleCollisions = true, PairFilter = filter });
        var before = world.State.ToArray();
        var e = Assert.Throws<InvalidOperationException>(() => world.Step(method, Dt));
        Assert.Contains("during its own step", e.Message, StringComparison.Ordinal);
        Assert.True(filter.Calls > 0);
        Assert.Equal(before, world.State.ToArray());
        Assert.Equal(0.0, world.Time);
    }

    [Theory]
    [InlineData("semi-implicit-euler")]
    [InlineData("xpbd")]
    public void A_step_from_inside_a_constraint_set_is_refused(string integrator)
    {
        var (world, method) = Ball(integrator);
        var set = new ReentrantConstraints(() => world.Step(method, Dt));
        world.AddConstraints(set);
        var before = world.State.ToArray();
        var e = Assert.Throws<InvalidOperationException>(() => world.Step(method, Dt));
        Assert.Contains("during its own step", e.Message, StringComparison.Ordinal);
        Assert.Equal(before, world.State.ToArray());
        Assert.Equal(0.0, world.Time);
    }

    [Theory]
    [InlineData(1)]
    [InlineData(3)]
    public void A_driver_frame_from_inside_a_step_is_refused_and_leaves_driver_and_world_as_they_were(int stepsPerFrame)
    {
        // The inner driver's frame must not begin a frame bracket it cannot close: after the refused call, a failed
        // step must still put the rods' tensions back (the world brackets single steps only outside frames).
        var (world, method) = Ball("rk4");
        world.AddParticle(new Vector3d(1, 0, 0), 1);
        world.Pin(1);
        var rods = new RodNetwork(world);
        rods.AddRod(0, 1, (world.GetPosition(0) - world.GetPosition(1)).Length);
        world.AddConstraints(rods);
        var driver = new FixedTimestepDriver(world, new RungeKutta4(), Dt, subSteps: stepsPerFrame);
        world.Step(method, Dt);
        var tension = rods.GetTension(0);
        var nested = new Reentrant(() => driver.Advance(Dt));
        world.AddForce(nested);
        var (accumulator, steps) = (driver.Accumulator, driver.StepCount);
        ExpectRefused(world, nested, () => world.Step(method, Dt));
        Assert.Equal(accumulator, driver.Accumulator);
        Assert.Equal(steps, driver.StepCount);
        Assert.Equal(tension, rods.GetTension(0));

        // The frame depth is still 0: a step that fails after its evaluations shows the tensions from before it.
        nested.Armed = false;
        world.DivergenceLimit = 1e-9;
        Assert.Throws<SimulationDivergedException>(() => world.Step(method, Dt));
        Assert.Equal(tension, rods.GetTension(0));
    }

    [Fact]
    public void A_driver_reset_from_inside_its_own_frame_is_refused_and_the_failed_frame_changes_nothing()
    {
        var (world, method) = Ball("rk4");
        var driver = new FixedTimestepDriver(world, method, Dt, subSteps: 2);
        driver.Advance(1.5 * Dt);
        var vertices = new Vector3[1];
        driver.InterpolatePositions(vertices);
        var (accumulator, before) = (driver.Accumulator, vertices[0]);
        foreach (var reset in new Action[] { driver.Reset, driver.ResetInterpolation })
        {
            var nested = new Reentrant(reset);
            world.AddForce(nested);
            Assert.Throws<InvalidOperationException>(() => driver.Advance(Dt));
            Assert.True(nested.Calls > 0);
            Assert.Equal(accumulator, driver.Accumulator);
            driver.InterpolatePositions(vertices);
            Assert.Equal(before, vertices[0]);
            world.RemoveForce(nested);
        }
    }

    [Fact]
    public void Every_setting_of_the_world_is_refused_from_inside_its_step()
    {
        var (world, method) = Ball("rk4");
        var snapshot = SimulationSnapshot.Capture(world);
        using var runner = new WorkerThreadRunner(2);
        var changes = new (string Name, Action Change)[]
        {
            ("Runner", () => world.Runner = runner),
            ("DivergenceLimit", () => world.DivergenceLimit = 5),
            ("Time", () => world.Time = 3),
            ("SetState", () => world.SetState(new double[6])),
            ("AddConstraints", () => world.AddConstraints(new ContactSet())),
            ("RestoreTo", () => snapshot.RestoreTo(world)),
        };

        foreach (var (name, change) in changes)
        {
            var nested = new Reentrant(change);
            world.AddForce(nested);
            var e = Assert.Throws<InvalidOperationException>(() => world.Step(method, Dt));
            Assert.True(e.Message.Contains("during its own step", StringComparison.Ordinal), $"{name}: {e.Message}");
            Assert.Null(world.Runner);
            Assert.Equal(ParticleWorld.DefaultDivergenceLimit, world.DivergenceLimit);
            Assert.Equal(0.0, world.Time);
            Assert.Empty(world.Constraints);
            world.RemoveForce(nested);
        }
    }

    [Fact]
    public void Kinematic_and_rod_settings_are_refused_from_inside_a_step_before_they_change_anything()
    {
        var (world, method) = Ball("rk4");
        world.AddParticle(new Vector3d(1, 1, 0), 1);
        var body = new KinematicBody(world, Vector3d.Zero, Rotation3d.Identity);
        body.Attach(1);
        var rods = new RodNetwork(world);
        var changes = new (string Name, Action Change)[]
        {
            ("Detach", () => body.Detach(1)),
            ("DriftStiffness", () => rods.DriftStiffness = 10),
            ("DriftDamping", () => rods.DriftDamping = 10),
        };

        foreach (var (name, change) in changes)
        {
            var nested = new Reentrant(change);
            world.AddForce(nested);
            var e = Assert.Throws<InvalidOperationException>(() => world.Step(method, Dt));
            Assert.True(e.Message.Contains("during its own step", StringComparison.Ordinal), $"{name}: {e.Message}");
            Assert.Equal(new[] { 1 }, body.Particles);
            Assert.True(world.IsPinned(1));
            Assert.Equal(0.0, rods.DriftStiffness);
            Assert.Equal(0.0, rods.DriftDamping);
            world.RemoveForce(nested);
        }
    }

    [Fact]
    public void The_worlds_own_force_elements_are_refused_from_inside_its_step()
    {
        // Springs, zero-length springs, dampers and a particle drag are built for one world: a force that added or
        // retuned them during a step changed the forces under the step, and kept the change when the step failed.
        var (world, method) = Ball("implicit-euler");
        world.AddParticle(new Vector3d(1, 1, 0), 1);
        var springs = new SpringNetwork(world);
        springs.Add(0, 1, 10, 1);
        var zero = new ZeroLengthSprings(world);
        zero.Add(0, 1, 5);
        var dampers = new Dampers(world);
        dampers.Add(0, 1, 0.5);
        var drag = new LinearDrag(0.1, world, new[] { 0 });
        foreach (var force in new IForceGenerator[] { springs, zero, dampers, drag })
        {
            world.AddForce(force);
        }

        var changes = new (string Name, Action Change)[]
        {
            ("SpringNetwork.Add", () => springs.Add(0, 1, 20, 2)),
            ("SpringNetwork.AddAnchored", () => springs.AddAnchored(0, Vector3d.Zero, 20, 2)),
            ("SpringNetwork.SetStiffness", () => springs.SetStiffness(0, 99)),
            ("SpringNetwork.SetDamping", () => springs.SetDamping(0, 9)),
            ("ZeroLengthSprings.Add", () => zero.Add(0, 1, 7)),
            ("ZeroLengthSprings.AddAnchored", () => zero.AddAnchored(0, Vector3d.Zero, 7)),
            ("ZeroLengthSprings.SetStiffness", () => zero.SetStiffness(0, 77)),
            ("ZeroLengthSprings.SetAnchor", () => zero.SetAnchor(0, Vector3d.Zero)),
            ("Dampers.Add", () => dampers.Add(0, 1, 3)),
            ("Dampers.SetDamping", () => dampers.SetDamping(0, 3)),
            ("LinearDrag.Coefficient", () => drag.Coefficient = 3),
        };

        ISpringElements[] elements = { springs, zero };
        var versions = Array.ConvertAll(elements, e => (e.TopologyVersion, e.ParameterVersion));
        foreach (var (name, change) in changes)
        {
            var nested = new Reentrant(change);
            world.AddForce(nested);
            var e = Assert.Throws<InvalidOperationException>(() => world.Step(method, Dt));
            Assert.True(e.Message.Contains("during its own step", StringComparison.Ordinal), $"{name}: {e.Message}");
            world.RemoveForce(nested);
            Assert.Equal(versions, Array.ConvertAll(elements, e => (e.TopologyVersion, e.ParameterVersion)));
        }

        Assert.Equal((1, 0), (springs.Count, springs.AnchoredCount));
        Assert.Equal((1, 0), (zero.Count, zero.AnchoredCount));
        Assert.Equal(1, dampers.Count);
        Assert.Equal(0.1, drag.Coefficient);
    }

    [Fact]
    public void Another_world_may_be_stepped_from_inside_a_force()
    {
        // The refusal is per world: a force may advance a world of its own (with an integrator of its own).
        var (world, method) = Ball("rk4");
        var (other, otherMethod) = Ball("rk4");
        world.AddForce(new Reentrant(() => other.Step(otherMethod, Dt)) { Repeat = true });
        world.Step(method, Dt);
        Assert.Equal(Dt, world.Time, 15);
        Assert.Equal(4 * Dt, other.Time, 15); // rk4 evaluates the forces four times per step
    }

    private static (ParticleWorld World, IIntegrator Method) Ball(string integrator)
    {
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(0, 1, 0), 1);
        world.AddForce(new Gravity());
        return (world, IntegratorCatalog.Create(integrator));
    }

    private static void ExpectRefused(ParticleWorld world, Reentrant nested, Action step)
    {
        var (before, time) = (world.State.ToArray(), world.Time);
        var e = Assert.Throws<InvalidOperationException>(step);
        Assert.Contains("during its own step", e.Message, StringComparison.Ordinal);
        Assert.True(nested.Calls > 0);
        Assert.Equal(before, world.State.ToArray());
        Assert.Equal(time, world.Time);
    }

    /// <summary>A force that runs an action once (or every time) it is evaluated, adding nothing.</summary>
    private sealed class Reentrant : IForceGenerator
    {
        private readonly Action _action;

        public Reentrant(Action action)
        {
            _action = action;
        }

        public bool Armed { get; set; } = true;

        public bool Repeat { get; set; }

        public int Calls { get; private set; }

        public void AddForces(in ParticleState state, Span<double> forces)
        {
            if (Armed && (Repeat || Calls == 0))
            {
                Calls++;
                _action();
            }
        }
    }

    private sealed class ReentrantFilter : IContactPairFilter
    {
        private readonly Action _action;

        public ReentrantFilter(Action action)
        {
            _action = action;
        }

        public int Calls { get; private set; }

        public bool MayCollide(int first, int second)
        {
            if (Calls++ == 0)
            {
                _action(); // once: before the fix, the nested step called the filter again, and that again
            }

            return true;
        }
    }

    private sealed class ReentrantConstraints : IConstraintSet
    {
        private readonly Action _action;
        private int _calls;

        public ReentrantConstraints(Action action)
        {
            _action = action;
        }

        public void Resolve(in ConstraintContext context) => Once();

        public void Project(in ConstraintContext context) => Once();

        public void SolveVelocities(in ConstraintContext context)
        {
        }

        private void Once()
        {
            if (_calls++ == 0)
            {
                _action();
            }
        }
    }
}
