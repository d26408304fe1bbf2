using System;
using System.Collections.Generic;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Tests.Engine;

/// <summary>
/// The constraint stage of a step: after the integrator, every constraint set corrects the end state, knowing the
/// start; a set that throws leaves the world as it was.
/// </summary>
public class ConstraintStageTests
{
    /// <summary>The catalog's integrators but the position-based ones, which project the sets in their substeps (XpbdTests).</summary>
    public static TheoryData<string> ForceBasedIntegrators()
    {
        var data = new TheoryData<string>();
        foreach (var name in IntegratorCatalog.Names)
        {
            if (!IntegratorCatalog.IsPositionBased(name))
            {
                data.Add(name);
            }
        }

        return data;
    }

    [Theory]
    [MemberData(nameof(ForceBasedIntegrators))]
    public void Every_force_based_integrator_is_followed_by_the_stage(string integrator)
    {

        // A floor that only the stage knows about: a falling particle never goes below it, whatever the integrator.
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(0, 1, 0), 1);
        world.AddForce(new Gravity());
        var floor = new Floor();
        world.AddConstraints(floor);
        var stepper = IntegratorCatalog.Create(integrator);
        for (var step = 0; step < 100; step++)
        {
            world.Step(stepper, 0.01);
            Assert.True(world.GetPosition(0).Y >= 0.0, $"below the floor at step {step}");
        }

        Assert.Equal(0.0, world.GetPosition(0).Y);
        Assert.Equal(100, floor.Calls);
    }

    [Fact]
    public void The_stage_sees_the_start_of_the_step_the_integrators_end_and_the_step_itself()
    {
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(0, 2, 0), new Vector3d(1, 0, 0), 3);
        world.Time = 0.5;
        var probe = new Probe();
        world.AddConstraints(probe);
        world.Step(new ExplicitEuler(), 0.25);

        Assert.Equal(new[] { 0.5, 0.25, 0.0, 2.0, 1.0, 0.25, 2.0, 1.0, 3.0, 1.0 / 3.0 }, probe.Seen);
    }

    [Fact]
    public void Sets_apply_in_the_order_they_were_added_and_can_be_removed()
    {
        var world = new ParticleWorld();
        world.AddParticle(Vector3d.Zero, 1);
        var order = new List<string>();
        var first = new Recorder("first", order);
        var second = new Recorder("second", order);
        world.AddConstraints(first);
        world.AddConstraints(second);
        Assert.Throws<ArgumentException>(() => world.AddConstraints(first));
        world.Step(new RungeKutta4(), 0.1);
        Assert.True(world.RemoveConstraints(first));
        Assert.False(world.RemoveConstraints(first));
        world.Step(new RungeKutta4(), 0.1);
        Assert.Equal(new[] { "first", "second", "second" }, order);
        Assert.Equal(new IConstraintSet[] { second }, world.Constraints);
    }

    [Fact]
    public void A_set_that_throws_leaves_the_world_exactly_as_it_was()
    {
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(0, 1, 0), new Vector3d(2, 0, 0), 1);
        world.AddForce(new Gravity());
        world.AddConstraints(new Floor());
        world.AddConstraints(new Throwing());
        var before = world.State.ToArray();
        Assert.Throws<InvalidOperationException>(() => world.Step(new RungeKutta4(), 0.01));
        Assert.Equal(before, world.State.ToArray());
        Assert.Equal(0.0, world.Time);
    }

    [Fact]
    public void A_set_that_pushes_the_state_past_the_limit_is_caught_like_a_diverged_integrator()
    {
        var world = new ParticleWorld();
        world.AddParticle(Vector3d.Zero, 1);
        world.AddConstraints(new Launcher());
        var e = Assert.Throws<SimulationDivergedException>(() => world.Step(new RungeKutta4(), 0.01));
        Assert.Equal(0, e.Particle);
        Assert.Equal(Vector3d.Zero, world.GetPosition(0));
    }

    /// <summary>y &gt;= 0: positions below are lifted onto it and their downward velocity removed.</summary>
    private sealed class Floor : IConstraintSet
    {
        public int Calls { get; private set; }

        public void Resolve(in ConstraintContext context)
        {
            Calls++;
            for (var i = 0; i < context.Count; i++)
            {
                if (context.Positions[(3 * i) + 1] < 0.0)
                {
                    context.Positions[(3 * i) + 1] = 0.0;
                    context.Velocities[(3 * i) + 1] = Math.Max(0.0, context.Velocities[(3 * i) + 1]);
                }
            }
        }

        public void Project(in ConstraintContext context) => Resolve(context);

        public void SolveVelocities(in ConstraintContext context)
        {
        }
    }

    private sealed class Probe : IConstraintSet
    {
        public double[] Seen { get; private set; } = Array.Empty<double>();

        public void Resolve(in ConstraintContext context) => Seen = new[]
        {
            context.Time, context.Dt, context.StartPositions[0], context.StartPositions[1], context.StartVelocities[0],
            context.Positions[0], context.Positions[1], context.Velocities[0], context.Masses[0], context.InverseMasses[0],
        };

        public void Project(in ConstraintContext context)
        {
        }

        public void SolveVelocities(in ConstraintContext context)
        {
        }
    }

    private sealed class Recorder : IConstraintSet
    {
        private readonly string _name;
        private readonly List<string> _order;

        public Recorder(string name, List<string> order)
        {
            _name = name;
            _order = order;
        }

        public void Resolve(in ConstraintContext context) => _order.Add(_name);

        public void Project(in ConstraintContext context)
        {
        }

        public void SolveVelocities(in ConstraintContext context)
        {
        }
    }

    private sealed class Throwing : IConstraintSet
    {
        public void Resolve(in ConstraintContext context)
        {
            context.Positions[0] = 42; // a half-done correction must not reach the world
            throw new InvalidOperationException("a constraint set failed");
        }

        public void Project(in ConstraintContext context)
        {
        }

        public void SolveVelocities(in ConstraintContext context)
        {
        }
    }

    private sealed class Launcher : IConstraintSet
    {
        public void Resolve(in ConstraintContext context) => context.Velocities[0] = 1e300;

        public void Project(in ConstraintContext context)
        {
        }

        public void SolveVelocities(in ConstraintContext context)
        {
        }
    }
}
