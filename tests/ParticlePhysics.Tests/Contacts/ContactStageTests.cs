using System;
using System.Linq;
using ParticlePhysics.Contacts;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Contacts;

/// <summary>The contact set as a stage of the world's step: allocation-free, deterministic, all or nothing, with checked inputs.</summary>
[Collection(AllocationMeasurements.Name)]
public class ContactStageTests
{
    [Theory]
    [InlineData("rk4")]
    [InlineData("implicit-euler")]
    [InlineData("semi-implicit-euler")]
    public void Stepping_a_pile_and_a_draped_cloth_allocates_nothing(string integrator)
    {
        foreach (var world in new[] { new ParticleBoxScenario { Count = 300 }.Build(), new DrapeScenario().Build() })
        {
            // Warm: the buffers grow to the contact counts once the particles have landed.
            var stepper = IntegratorCatalog.Create(integrator);
            StateMetrics.Run(world, stepper, 0.001, 300);
            Assert.Equal(0, ThreadAllocations.Measure(() => StateMetrics.Run(world, stepper, 0.001, 100)));
        }
    }

    [Fact]
    public void Substeps_allocate_nothing_once_warm()
    {
        var world = new ParticleBoxScenario { Count = 200 }.Build();
        var set = world.Constraints.OfType<ContactSet>().Single();
        var n = world.Count;
        var start = world.State.ToArray();
        var x = start.AsSpan(0, 3 * n).ToArray();
        var v = start.AsSpan(3 * n).ToArray();
        void Substep()
        {
            var context = new ConstraintContext(0, 1e-3, start.AsSpan(0, 3 * n), start.AsSpan(3 * n), x, v, world.Masses, world.InverseMasses, world.Radii);
            set.Project(in context);
            set.SolveVelocities(in context);
        }

        Substep();
        Assert.Equal(0, ThreadAllocations.Measure(() =>
        {
            for (var k = 0; k < 20; k++)
            {
                Substep();
            }
        }));
    }

    [Fact]
    public void A_step_allocates_in_proportion_to_the_pairs_it_finds_not_sixteen_queue_entries_per_pair()
    {
        // Issue 27, item 7: 10,000 particles at one point (50 million candidate pairs) ran out of memory, because the
        // impact queue was sized at 16 entries per candidate pair up front (24 bytes each: 384 bytes a pair), though
        // a pile at rest queues almost nothing. The stage's buffers indexed by pair take about 40 bytes a pair (the
        // grid's list, the pairs, each particle's pairs, the shock pass's ranks), twice that while they double.
        const int count = 600;
        var world = new ParticleWorld();
        for (var i = 0; i < count; i++)
        {
            world.AddParticle(new Vector3d(0, 1, 0), 1);
            world.SetRadius(i, 0.01);
        }

        var contacts = new ContactSet { ParticleCollisions = true };
        world.AddConstraints(contacts);
        var rk4 = new RungeKutta4();
        var before = GC.GetAllocatedBytesForCurrentThread();
        world.Step(rk4, 1.0 / 60.0);
        var allocated = GC.GetAllocatedBytesForCurrentThread() - before;
        var pairs = count * (count - 1) / 2;
        Assert.Equal(pairs, contacts.CandidatePairCount);
        Assert.True(allocated < 128L * pairs, $"{allocated} bytes for {pairs} pairs: {(double)allocated / pairs:F0} a pair");
    }

    [Fact]
    public void A_step_that_would_pass_the_candidate_pair_limit_is_refused_with_nothing_changed()
    {
        var world = new ParticleWorld();
        for (var i = 0; i < 100; i++)
        {
            world.AddParticle(new Vector3d(0, 1, 0), 1);
            world.SetRadius(i, 0.01);
        }

        var contacts = new ContactSet { ParticleCollisions = true, MaxCandidatePairs = 4949 };
        world.AddConstraints(contacts);
        var before = world.State.ToArray();
        foreach (var stepper in new IIntegrator[] { new RungeKutta4(), new Xpbd() })
        {
            var refusal = Assert.Throws<InvalidOperationException>(() => world.Step(stepper, 1.0 / 60.0));
            Assert.Contains("MaxCandidatePairs", refusal.Message);
            Assert.Contains("4949", refusal.Message);
            Assert.Equal(before, world.State.ToArray());
            Assert.Equal(0.0, world.Time);
            Assert.Equal(0, contacts.CandidatePairCount);
        }

        contacts.MaxCandidatePairs = 4950;
        world.Step(new RungeKutta4(), 1.0 / 60.0);
        Assert.Equal(4950, contacts.CandidatePairCount);
        Assert.Throws<ArgumentOutOfRangeException>(() => contacts.MaxCandidatePairs = 0);
        Assert.Throws<ArgumentOutOfRangeException>(() => contacts.MaxCandidatePairs = ContactSet.DefaultMaxCandidatePairs + 1);
    }

    [Fact]
    public void A_repeated_run_gives_bit_identical_states()
    {
        static string Run()
        {
            var world = new ParticleBoxScenario { Count = 300, Restitution = 0.3 }.Build();
            StateMetrics.Run(world, new RungeKutta4(), 1.0 / 120.0, 120);
            return StateMetrics.BitHash(world.State);
        }

        Assert.Equal(Run(), Run());
    }

    [Fact]
    public void A_contact_set_that_fails_leaves_the_world_as_it_was()
    {
        // An obstacle that launches the particle past the divergence limit: the step throws and nothing is committed.
        var world = new BouncingBallScenario().Build();
        var ground = (PlaneObstacle)world.Constraints.OfType<ContactSet>().Single().Obstacles[0];
        ground.Velocity = new Vector3d(0, 1e13, 0);
        ground.Restitution = 1;
        var before = world.State.ToArray();
        Assert.Throws<SimulationDivergedException>(() => world.Step(new RungeKutta4(), 0.001));
        Assert.Equal(before, world.State.ToArray());
        Assert.Equal(0.0, world.Time);
    }

    [Fact]
    public void Bad_values_are_refused_with_their_name()
    {
        Assert.Equal("Restitution", Assert.Throws<ArgumentOutOfRangeException>(() => new SphereObstacle(Vector3d.Zero, 1, restitution: 1.5)).ParamName);
        Assert.Equal("Friction", Assert.Throws<ArgumentOutOfRangeException>(() => PlaneObstacle.Ground(0, -0.1)).ParamName);
        Assert.Equal("Radius", Assert.Throws<ArgumentOutOfRangeException>(() => new SphereObstacle(Vector3d.Zero, 0)).ParamName);
        Assert.Equal("Radius", Assert.Throws<ArgumentOutOfRangeException>(() => new CapsuleObstacle(Vector3d.Zero, Vector3d.Zero, double.NaN)).ParamName);
        Assert.Equal("Normal", Assert.Throws<ArgumentOutOfRangeException>(() => new PlaneObstacle(Vector3d.Zero, Vector3d.Zero)).ParamName);
        Assert.Equal("HalfExtents.Y", Assert.Throws<ArgumentOutOfRangeException>(() => new BoxObstacle(Vector3d.Zero, new Vector3d(1, -1, 1))).ParamName);
        var box = new BoxObstacle(Vector3d.Zero, new Vector3d(1, 1, 1));
        Assert.Equal("axisY", Assert.Throws<ArgumentOutOfRangeException>(() => box.SetOrientation(new Vector3d(1, 0, 0), new Vector3d(2, 0, 0))).ParamName);
        Assert.Equal("Velocity", Assert.Throws<ArgumentOutOfRangeException>(() => box.Velocity = new Vector3d(double.NaN, 0, 0)).ParamName);
        var set = new ContactSet();
        Assert.Throws<ArgumentOutOfRangeException>(() => set.RestingSpeed = -1);
        Assert.Throws<ArgumentOutOfRangeException>(() => set.ParticleRestitution = 2);
        Assert.Throws<ArgumentOutOfRangeException>(() => set.ParticleFriction = double.PositiveInfinity);
        Assert.Throws<ArgumentOutOfRangeException>(() => set.ProjectionIterations = 0);
        set.Add(box);
        Assert.Throws<ArgumentException>(() => set.Add(box));
        for (var k = 1; k < 1000; k++)
        {
            set.Add(PlaneObstacle.Ground()); // any number (there was a limit of 64)
        }

        Assert.Equal(1000, set.Obstacles.Count);
        Assert.True(set.Remove(box));
        Assert.False(set.Remove(box));
    }

    [Fact]
    public void The_world_checks_radii_like_masses_and_hands_them_to_the_stage()
    {
        var world = new ParticleWorld();
        world.AddParticle(Vector3d.Zero, 1);
        Assert.Equal(0.0, world.GetRadius(0));
        Assert.Equal("radius", Assert.Throws<ArgumentOutOfRangeException>(() => world.SetRadius(0, -0.1)).ParamName);
        Assert.Equal("radius", Assert.Throws<ArgumentOutOfRangeException>(() => world.SetRadius(0, double.NaN)).ParamName);
        Assert.Equal("index", Assert.Throws<ArgumentOutOfRangeException>(() => world.SetRadius(1, 0.1)).ParamName);
        world.SetRadius(0, 0.25);
        Assert.Equal(new[] { 0.25 }, world.Radii.ToArray());
        Assert.Throws<ArgumentException>(() => new ConstraintContext(0, 1, new double[3], new double[3], new double[3], new double[3], new double[1], new double[1], new double[2]));
    }
}
