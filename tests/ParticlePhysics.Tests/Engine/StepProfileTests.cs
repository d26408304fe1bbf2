using System;
using System.Diagnostics;
using ParticlePhysics.Contacts;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Internal;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Engine;

/// <summary>
/// The world's per-stage timings (<see cref="ParticleWorld.LastStepProfile"/>): the counts are exactly the calls each
/// integrator makes, the times are non-negative and add up to the step's, profiling changes no bit, and a failed step
/// leaves the last profile as it was.
/// </summary>
public class StepProfileTests
{
    [Fact]
    public void Rk4_evaluates_the_forces_four_times_and_the_rod_adds_its_forces_in_each_then_resolves_once()
    {
        var world = new PendulumScenario().Build();
        world.Profiling = true;
        world.Step(new RungeKutta4(), 0.01);

        var profile = world.LastStepProfile;
        Assert.Equal(4, profile.ForceEvaluations);
        Assert.Equal(4 + 1, profile.ConstraintCalls); // AddConstraintForces in each evaluation, then Resolve
        Assert.Equal(0, profile.JacobianProducts);
        Assert.Equal(0, profile.Substeps);
        Assert.Equal(0, profile.ContactCalls);
        AssertTimesAddUp(profile);
    }

    [Theory]
    [InlineData(1)]
    [InlineData(7)]
    public void Xpbd_evaluates_projects_and_solves_velocities_once_per_substep(int substeps)
    {
        var world = new ClothScenario { Resolution = 1.0 / 7 }.Build(); // its springs' projection: one set
        Assert.Single(world.Constraints);
        world.Profiling = true;
        world.Step(new Xpbd(substeps), 1.0 / 60);

        var profile = world.LastStepProfile;
        Assert.Equal(substeps, profile.ForceEvaluations);
        Assert.Equal(substeps, profile.Substeps);
        Assert.Equal(2 * substeps, profile.ConstraintCalls); // Project, then SolveVelocities
        Assert.Equal(0, profile.JacobianProducts);
        AssertTimesAddUp(profile);
    }

    [Fact]
    public void Implicit_euler_evaluates_once_and_takes_one_product_per_iteration_without_a_warm_start()
    {
        var world = new ClothScenario { Resolution = 1.0 / 15 }.Build();
        world.Profiling = true;
        var implicitEuler = new ImplicitEuler { WarmStart = false };
        for (var step = 0; step < 3; step++)
        {
            world.Step(implicitEuler, 1.0 / 60);
            var profile = world.LastStepProfile;
            Assert.Equal(1, profile.ForceEvaluations); // forces and linearisation in one call
            Assert.True(implicitEuler.LastIterations > 0);
            Assert.Equal(implicitEuler.LastIterations, profile.JacobianProducts);
            Assert.Equal(1, profile.ConstraintCalls); // the springs' projection, which does nothing here
            AssertTimesAddUp(profile);
        }
    }

    [Fact]
    public void A_contact_stage_is_booked_as_contacts_with_the_broad_phase_and_counts_it_reports()
    {
        var world = new PendulumScenario().Build();
        var contacts = new FakeContactStage();
        world.AddConstraints(contacts);
        world.Profiling = true;
        world.Step(new SemiImplicitEuler(), 0.01);

        var profile = world.LastStepProfile;
        Assert.Equal(1, profile.ForceEvaluations);
        Assert.Equal(1 + 1, profile.ConstraintCalls); // the rod's forces and its Resolve; not the contact stage
        Assert.Equal(1, profile.ContactCalls);
        Assert.Equal(FakeContactStage.PairsPerCall, profile.ContactPairs);
        Assert.Equal(FakeContactStage.ContactsPerCall, profile.Contacts);
        Assert.True(profile.BroadPhaseSeconds > 0.0);
        Assert.True(profile.BroadPhaseSeconds <= profile.ContactSeconds);
        Assert.Equal(1, contacts.Begun);
        Assert.Equal(1, contacts.Ended);
        AssertTimesAddUp(profile);

        world.Step(new Xpbd(3), 0.01);
        profile = world.LastStepProfile;
        Assert.Equal(2 * 3, profile.ContactCalls); // Project and SolveVelocities in each substep
        Assert.Equal(2 * 3 * FakeContactStage.PairsPerCall, profile.ContactPairs);
        Assert.Equal(2, contacts.Ended);
    }

    [Theory]
    [InlineData("rk4")]
    [InlineData("xpbd")]
    public void The_contact_set_is_booked_as_contacts_with_its_broad_phase_pairs_and_contacts(string integrator)
    {
        // Ten balls dropped in a box: after a second they touch the floor, and each other where they pile up.
        var world = new ParticleWorld();
        world.AddForce(new Gravity());
        for (var i = 0; i < 10; i++)
        {
            world.AddParticle(new Vector3d(0.05 * (i % 3), 0.1 + (0.15 * i), 0.05 * (i / 3 % 3)), 1.0);
            world.SetRadius(i, 0.05);
        }

        var contacts = new ContactSet { ParticleCollisions = true };
        contacts.Add(new PlaneObstacle(Vector3d.Zero, new Vector3d(0, 1, 0)));
        world.AddConstraints(contacts);
        var stepper = IntegratorCatalog.Create(integrator);
        for (var s = 0; s < 100; s++)
        {
            world.Step(stepper, 0.01);
        }

        world.Profiling = true;
        world.Step(stepper, 0.01);
        var profile = world.LastStepProfile;
        Assert.Equal(integrator == "xpbd" ? 2 * profile.Substeps : 1, profile.ContactCalls);
        Assert.Equal(0, profile.ConstraintCalls);
        Assert.True(profile.ContactPairs > 0, "the balls are near each other: the broad phase lists pairs");
        Assert.True(profile.Contacts >= 1, "at least the lowest ball rests on the floor");
        Assert.True(profile.ContactSeconds > 0.0);
        Assert.True(profile.BroadPhaseSeconds > 0.0);
        Assert.True(profile.BroadPhaseSeconds <= profile.ContactSeconds);
        AssertTimesAddUp(profile);
    }

    [Theory]
    [InlineData("rk4")]
    [InlineData("implicit-euler")]
    [InlineData("xpbd")]
    public void Profiling_changes_no_bit(string integrator)
    {
        foreach (var build in new Func<ParticleWorld>[]
        {
            () => new ClothScenario { Resolution = 1.0 / 11 }.Build(),
            new PendulumScenario().Build,
            new BouncingBallScenario().Build,
        })
        {
            var plain = build();
            var profiled = build();
            profiled.Profiling = true;
            StateMetrics.Run(plain, IntegratorCatalog.Create(integrator), 0.005, 40);
            StateMetrics.Run(profiled, IntegratorCatalog.Create(integrator), 0.005, 40);
            Assert.Equal(StateMetrics.BitHash(plain.State), StateMetrics.BitHash(profiled.State));
            Assert.Equal(default, plain.LastStepProfile);
            Assert.NotEqual(default, profiled.LastStepProfile);
        }
    }

    [Fact]
    public void A_failed_step_leaves_the_last_profile_and_a_step_with_profiling_off_clears_it()
    {
        var world = new PendulumScenario().Build();
        var fault = new FaultyForce();
        world.AddForce(fault);
        var contacts = new FakeContactStage();
        world.AddConstraints(contacts);
        world.Profiling = true;
        var rk4 = new RungeKutta4();
        world.Step(rk4, 0.01);
        var last = world.LastStepProfile;
        Assert.Equal(4, last.ForceEvaluations);

        fault.Arm(Fault.Throw, afterEvaluations: 2);
        Assert.Throws<InvalidOperationException>(() => world.Step(rk4, 0.01));
        Assert.Equal(last, world.LastStepProfile);
        Assert.Equal(contacts.Begun, contacts.Ended); // the contact stage stopped timing with the failed step

        fault.Arm(Fault.None);
        world.Profiling = false;
        world.Step(rk4, 0.01);
        Assert.Equal(default, world.LastStepProfile);
        Assert.Equal(2, contacts.Begun); // not told to time a step that is not profiled
    }

    [Fact]
    public void Profiling_cannot_be_switched_from_inside_the_step()
    {
        var world = new ParticleWorld();
        world.AddParticle(Vector3d.Zero, 1.0);
        world.AddForce(new SwitchesProfiling(world));
        Assert.Throws<InvalidOperationException>(() => world.Step(new ExplicitEuler(), 0.01));
        Assert.False(world.Profiling);
        Assert.Equal(0.0, world.Time);
    }

    [Fact]
    public void Profiles_add_up_stage_by_stage()
    {
        var world = new PendulumScenario().Build();
        world.Profiling = true;
        var sum = default(StepProfile);
        var totals = 0.0;
        for (var step = 0; step < 5; step++)
        {
            world.Step(new RungeKutta4(), 0.01);
            sum += world.LastStepProfile;
            totals += world.LastStepProfile.TotalSeconds;
        }

        Assert.Equal(20, sum.ForceEvaluations);
        Assert.Equal(25, sum.ConstraintCalls);
        Assert.Equal(totals, sum.TotalSeconds);
        Assert.Contains("20 evaluations", sum.ToString(), StringComparison.Ordinal);
    }

    /// <summary>Every time non-negative, and the stages (integration the rest) adding up to the total.</summary>
    internal static void AssertTimesAddUp(StepProfile profile)
    {
        Assert.True(profile.TotalSeconds > 0.0);
        Assert.True(profile.ForceSeconds >= 0.0);
        Assert.True(profile.ConstraintSeconds >= 0.0);
        Assert.True(profile.ContactSeconds >= 0.0);
        Assert.True(profile.BroadPhaseSeconds >= 0.0);
        Assert.True(profile.IntegrationSeconds >= 0.0);
        var stages = profile.ForceSeconds + profile.ConstraintSeconds + profile.ContactSeconds;
        Assert.True(stages <= profile.TotalSeconds * (1 + 1e-12), $"{stages} s of stages in a step of {profile.TotalSeconds} s");
        Assert.Equal(profile.TotalSeconds, stages + profile.IntegrationSeconds, 12);
    }

    /// <summary>
    /// A constraint set that says it is a contact stage (as <see cref="ContactSet"/> will): it changes nothing, spends a
    /// measured moment in a "broad phase" per call, and reports fixed counts.
    /// </summary>
    internal sealed class FakeContactStage : IConstraintSet, IContactStage
    {
        public const int PairsPerCall = 3;
        public const int ContactsPerCall = 2;
        private bool _timing;
        private long _ticks;
        private int _pairs;
        private int _contacts;

        public int Begun { get; private set; }

        public int Ended { get; private set; }

        public void Resolve(in ConstraintContext context) => Call();

        public void Project(in ConstraintContext context) => Call();

        public void SolveVelocities(in ConstraintContext context) => Call();

        public void BeginProfile()
        {
            Begun++;
            _timing = true;
            _ticks = 0;
            _pairs = 0;
            _contacts = 0;
        }

        public void EndProfile(out long broadPhaseTicks, out int pairs, out int contacts)
        {
            Ended++;
            _timing = false;
            broadPhaseTicks = _ticks;
            pairs = _pairs;
            contacts = _contacts;
        }

        private void Call()
        {
            if (!_timing)
            {
                return;
            }

            var started = Stopwatch.GetTimestamp();
            while (Stopwatch.GetTimestamp() == started)
            {
            }

            _ticks += Stopwatch.GetTimestamp() - started;
            _pairs += PairsPerCall;
            _contacts += ContactsPerCall;
        }
    }

    private sealed class SwitchesProfiling : IForceGenerator
    {
        private readonly ParticleWorld _world;

        public SwitchesProfiling(ParticleWorld world) => _world = world;

        public void AddForces(in ParticleState state, Span<double> forces) => _world.Profiling = true;
    }
}
