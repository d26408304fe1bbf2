using System;
using System.Collections.Generic;
using System.Linq;
using ParticlePhysics.Cloth;
using ParticlePhysics.Constraints;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Constraints;

/// <summary>
/// xpbd: springs projected with compliance 1 / k, every constraint set once per substep, stable at 60 Hz at any
/// stiffness, and converging to the force-based solution as the substeps shrink.
/// </summary>
public class XpbdTests
{
    [Theory]
    [InlineData(1e4)]
    [InlineData(1e8)]
    [InlineData(25)]
    public void The_static_sag_on_a_compliant_constraint_is_m_g_alpha_whatever_the_substeps(double stiffness)
    {
        const double mass = 2;
        var expected = mass * 9.81 / stiffness;
        foreach (var substeps in new[] { 1, 3, 10, 100 })
        {
            // From the unstretched length, critically damped, at 60 Hz.
            var world = HangingSpring(stiffness, mass, damping: 2 * Math.Sqrt(stiffness * mass), out _);
            StateMetrics.Run(world, new Xpbd(substeps), 1.0 / 60, 1200);
            var sag = -world.GetPosition(0).Y - 1;
            Assert.True(Math.Abs(sag - expected) < Math.Max(1e-9 * expected, 1e-14), $"k = {stiffness}, {substeps} substeps: sag {sag:R}, m g alpha = {expected:R}");

            // And at the sag it is a fixed point, to rounding, from the first step.
            var resting = HangingSpring(stiffness, mass, damping: 0, out _);
            resting.SetPosition(0, new Vector3d(0, -1 - expected, 0));
            StateMetrics.Run(resting, new Xpbd(substeps), 1.0 / 60, 10);
            Assert.Equal(-1 - expected, resting.GetPosition(0).Y, 1e-13);
            Assert.Equal(0, resting.GetVelocity(0).Y, 1e-10);
        }
    }

    [Theory]
    [InlineData(1e3, false, 0.0)]
    [InlineData(1e9, false, 0.0)]
    [InlineData(1e300, false, 0.0)]
    [InlineData(double.MaxValue, false, 0.0)]
    [InlineData(1e300, true, 0.0)]
    [InlineData(double.MaxValue, true, 0.0)]
    [InlineData(1e300, true, 1e-3)]
    [InlineData(double.MaxValue, true, 1e-3)]
    public void A_spring_on_a_light_particle_tends_to_the_rigid_projection_as_k_grows(double stiffness, bool pair, double damping)
    {
        // With damping 0 the pair spring takes the projection's undamped path, with damping its general one: both
        // must reach the limit.
        // Issue 27, item 10: on a 1e-6 kg particle, k = double.MaxValue made (k h^2 + c h) w overflow: the denominator
        // was infinite, the correction 0, and the spring 5 m long after 1 s of free fall instead of 1 m. The length
        // after 1 s hanging at 60 Hz is 1 + m g / k, the rigid rod's 1 m in the limit.
        const double mass = 1e-6;
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(0, -1, 0), mass);
        world.AddParticle(Vector3d.Zero, mass);
        world.Pin(1);
        var springs = new SpringNetwork(world);
        if (pair)
        {
            springs.Add(0, 1, stiffness, 1, damping);
        }
        else
        {
            springs.AddAnchored(0, Vector3d.Zero, stiffness, 1, 0.0);
        }

        world.AddForce(springs);
        world.AddForce(new Gravity());
        world.AddConstraints(new SpringProjection(springs));
        StateMetrics.Run(world, new Xpbd(), 1.0 / 60, 60);
        var length = world.GetPosition(0).Length;
        var expected = 1 + (mass * 9.81 / stiffness);
        Assert.True(Math.Abs(length - expected) < 1e-9, $"k = {stiffness:R}: length {length:R} m, expected {expected:R}");

        // At k = double.MaxValue the spring is the rod of xpbd's compliance 0, to rounding.
        if (stiffness == double.MaxValue)
        {
            var rod = new ParticleWorld();
            rod.AddParticle(new Vector3d(0, -1, 0), mass);
            var rods = new RodNetwork(rod);
            rods.AddAnchoredRod(0, Vector3d.Zero, 1);
            rod.AddConstraints(rods);
            rod.AddForce(new Gravity());
            StateMetrics.Run(rod, new Xpbd(), 1.0 / 60, 60);
            Assert.True((rod.GetPosition(0) - world.GetPosition(0)).Length < 1e-12, $"{rod.GetPosition(0)} vs {world.GetPosition(0)}");
        }
    }

    [Theory]
    [InlineData(50)]
    [InlineData(1e4)]
    [InlineData(1e7)]
    [InlineData(1e12)]
    public void The_cloth_is_stable_at_60_hz_at_any_stiffness(double stiffness)
    {
        var world = new ClothScenario { Stiffness = stiffness }.Build();
        var xpbd = new Xpbd();
        StateMetrics.Run(world, xpbd, 1.0 / 60, 600);
        var positions = world.Positions.ToArray();
        Assert.All(positions, p => Assert.True(Math.Abs(p) < 3, $"a particle at {p}"));
        var slowest = Enumerable.Range(0, world.Count).Max(i => world.GetVelocity(i).Length);
        Assert.True(slowest < 0.5, $"k = {stiffness}: still moving at {slowest} m/s after 10 s");
    }

    [Fact]
    public void At_small_substeps_the_cloth_approaches_rk4s()
    {
        // The same cloth for 0.5 s: rk4 at 1e-4 s as the reference, xpbd at 1 ms with 1, 4 and 16 substeps. Measured:
        // 4.9e-3, 1.3e-3 and 3.4e-4 m, first order in the substep.
        var reference = new ClothScenario().Build();
        StateMetrics.Run(reference, new RungeKutta4(), 1e-4, 5000);
        var distances = new List<double>();
        foreach (var substeps in new[] { 1, 4, 16 })
        {
            var world = new ClothScenario().Build();
            StateMetrics.Run(world, new Xpbd(substeps), 1e-3, 500);
            distances.Add(StateMetrics.MaxAbsError(world.Positions, reference.Positions));
        }

        Assert.True(distances[2] < 5e-4, $"{distances[2]:E3} m from rk4");
        for (var d = 1; d < distances.Count; d++)
        {
            Assert.InRange(distances[d - 1] / distances[d], 3, 5);
        }
    }

    [Fact]
    public void Every_set_is_projected_once_per_substep_and_the_stage_after_the_step_does_not_run()
    {
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(0, 1, 0), 1);
        var counter = new Counter();
        world.AddConstraints(counter);
        world.Step(new Xpbd(7), 0.1);
        Assert.Equal((0, 7, 7), (counter.Resolved, counter.Projected, counter.Velocities));
        Assert.Equal(new[] { 0.1 / 7 }, counter.Substeps.Distinct());
        world.Step(new RungeKutta4(), 0.1);
        Assert.Equal((1, 7, 7), (counter.Resolved, counter.Projected, counter.Velocities));
    }

    [Fact]
    public void Projected_springs_are_left_out_of_the_predictions_accelerations()
    {
        var world = HangingSpring(100, 1, 0, out var springs);
        world.SetPosition(0, new Vector3d(0, -1.5, 0));
        IPositionBasedSystem system = world;
        var a = new double[3];
        system.ComputeUnprojectedAccelerations(0, world.Positions, world.Velocities, a);
        Assert.Equal(new[] { 0, -9.81, 0 }, a);
        world.ComputeAccelerations(0, world.Positions, world.Velocities, a);
        Assert.Equal(-9.81 + 50, a[1], 1e-12);

        // Without its projection the network is an ordinary force for xpbd too.
        Assert.True(world.RemoveConstraints(world.Constraints.OfType<SpringProjection>().Single()));
        system.ComputeUnprojectedAccelerations(0, world.Positions, world.Velocities, a);
        Assert.Equal(-9.81 + 50, a[1], 1e-12);
        _ = springs;
    }

    [Fact]
    public void Colours_are_independent_batches_computed_when_the_topology_changes()
    {
        var cloth = new ClothBuilder { Rows = 12, Columns = 9 }.Build();
        var projection = cloth.Projection;
        cloth.System.Step(new Xpbd(), 1.0 / 60);
        var order = projection.ProjectionOrder.ToArray();
        var starts = projection.BatchStarts.ToArray();
        Assert.Equal(cloth.Springs.Count, order.Length);
        Assert.Equal(Enumerable.Range(0, order.Length), order.OrderBy(s => s));
        for (var c = 0; c + 1 < starts.Length; c++)
        {
            var seen = new HashSet<int>();
            for (var k = starts[c]; k < starts[c + 1]; k++)
            {
                var (first, second) = cloth.Springs.GetEnds(order[k]);
                Assert.True(seen.Add(first) && seen.Add(second), $"colour {c} touches a particle twice");
            }
        }

        // With d = 12 springs at the most crowded particle, at least d colours and at most 2 d - 1.
        Assert.InRange(projection.ColourCount, 12, 23);

        // Retuning keeps the batches; a new spring brings new ones.
        cloth.Springs.SetStiffness(0, 80);
        cloth.System.Step(new Xpbd(), 1.0 / 60);
        Assert.Equal(order, projection.ProjectionOrder.ToArray());
        cloth.Springs.Add(0, 107, 1, 1.5);
        cloth.System.Step(new Xpbd(), 1.0 / 60);
        Assert.Equal(order.Length + 1, projection.ProjectionOrder.Length);
    }

    [Fact]
    public void Substeps_are_a_whole_number_from_1_to_1000_and_a_plain_ode_is_refused()
    {
        Assert.Equal(10, new Xpbd().Substeps);
        Assert.Equal(10, ((Xpbd)IntegratorCatalog.Create("xpbd")).Substeps);
        Assert.Equal(3, ((Xpbd)IntegratorCatalog.Create("xpbd", substeps: 3)).Substeps);
        Assert.Throws<ArgumentOutOfRangeException>(() => new Xpbd(0));
        Assert.Throws<ArgumentOutOfRangeException>(() => new Xpbd { Substeps = 1001 });
        var simulation = new OdeSimulation(new GaussianDecayOde(), new[] { 1.0 });
        var ex = Assert.Throws<ArgumentException>("system", () => simulation.Step(new Xpbd(), 0.1));
        Assert.Contains("position-based", ex.Message, StringComparison.Ordinal);
        Assert.False(IntegratorCatalog.AppliesTo("xpbd", new GaussianDecayOde()));
        Assert.True(IntegratorCatalog.AppliesTo("xpbd", new ClothScenario().Build()));
    }

    [Fact]
    public void Zero_length_springs_are_projected_too()
    {
        // The mass-spring-damper's spring (k = 1, zero rest length) under xpbd rests at m g / k below the anchor.
        var scenario = new MassSpringDamperScenario { Damping = 2 };
        var world = scenario.Build();
        StateMetrics.Run(world, new Xpbd(), 0.01, 3000);
        Assert.Equal(-9.81, world.GetPosition(0).Y, 1e-9);
        Assert.Contains(world.Constraints, c => c is SpringProjection);
    }

    [Fact]
    public void A_spring_from_a_particle_to_itself_is_refused_by_name()
    {
        var world = new ParticleWorld();
        world.AddParticle(Vector3d.Zero, 1);
        world.AddParticle(new Vector3d(1, 0, 0), 1);
        world.AddConstraints(new SpringProjection(new SelfSpring()));
        var before = world.State.ToArray();
        var ex = Assert.Throws<ArgumentException>(() => world.Step(new Xpbd(), 0.01));
        Assert.Contains("Spring 0 joins particle 1 to itself", ex.Message, StringComparison.Ordinal);
        Assert.Equal(before, world.State.ToArray());
    }

    private static ParticleWorld HangingSpring(double stiffness, double mass, double damping, out SpringNetwork springs)
    {
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(0, -1, 0), mass);
        springs = new SpringNetwork(world);
        springs.AddAnchored(0, Vector3d.Zero, stiffness, 1, damping);
        world.AddForce(springs);
        world.AddForce(new Gravity());
        world.AddConstraints(new SpringProjection(springs));
        return world;
    }

    /// <summary>Springs from elsewhere than a SpringNetwork (which refuses them): one joining particle 1 to itself.</summary>
    private sealed class SelfSpring : ISpringElements
    {
        public int TopologyVersion => 0;

        public int ParameterVersion => 0;

        public int PairCount => 1;

        public int AnchoredCount => 0;

        public void AddForces(in ParticleState state, Span<double> forces)
        {
        }

        public void CopyPairs(Span<int> first, Span<int> second, Span<double> parameters)
        {
            first[0] = second[0] = 1;
            parameters[0] = 10;
            parameters[1] = 1;
            parameters[2] = 0;
        }

        public void CopyAnchored(Span<int> particle, Span<double> parameters)
        {
        }
    }

    private sealed class Counter : IConstraintSet
    {
        public int Resolved { get; private set; }

        public int Projected { get; private set; }

        public int Velocities { get; private set; }

        public List<double> Substeps { get; } = new();

        public void Resolve(in ConstraintContext context) => Resolved++;

        public void Project(in ConstraintContext context)
        {
            Projected++;
            Substeps.Add(context.Dt);
        }

        public void SolveVelocities(in ConstraintContext context) => Velocities++;
    }
}
