using System;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Integrators.Multigrid;

namespace ParticlePhysics.Tests.Implicit;

/// <summary>
/// Issue 10, item 1: a Jacobian product reads only a linearisation that describes the forces as they are. Asked before
/// any Linearize, or after elements were added since, it throws InvalidOperationException and writes nothing; no
/// pointer loop reads or writes past its arrays.
/// </summary>
public class LinearizationBoundsTests
{
    [Fact]
    public void A_spring_network_product_after_springs_were_added_since_linearize_throws_and_writes_nothing()
    {
        // The fuzzer's case: 8 springs linearised, 2,000 present; the old pointer loop read 1,992 springs' worth of
        // memory past the end of the linearisation (300 non-zero garbage entries).
        var (world, springs) = Chain(2001, springs: 8);
        var n = world.CoordinateCount;
        springs.Linearize(world.View(), 1.0, 0.5, new double[n]);
        for (var s = 8; s < 2000; s++)
        {
            springs.Add(s, s + 1, 10, 0.1, 0.2);
        }

        var w = Ones(n);
        var result = new double[n];
        var e = Assert.Throws<InvalidOperationException>(() => springs.AddJacobianProduct(w, result));
        Assert.Contains("8 + 0", e.Message, StringComparison.Ordinal);
        Assert.Contains("2000 + 0", e.Message, StringComparison.Ordinal);
        Assert.All(result, v => Assert.Equal(0.0, v));
        var blocks = new double[3 * n];
        Assert.Throws<InvalidOperationException>(() => springs.AddDiagonalBlocks(blocks));
        Assert.All(blocks, v => Assert.Equal(0.0, v));

        // Linearised again, the product covers all 2,000 springs.
        springs.Linearize(world.View(), 1.0, 0.5, new double[n]);
        springs.AddJacobianProduct(w, result);
        Assert.All(result, v => Assert.True(double.IsFinite(v)));
    }

    [Fact]
    public void An_anchored_spring_added_since_linearize_is_caught_too()
    {
        var (world, springs) = Chain(3, springs: 2);
        springs.Linearize(world.View(), 1.0, 0.0, new double[9]);
        springs.AddAnchored(0, new Vector3d(0, 1, 0), 5, 0.5);
        Assert.Throws<InvalidOperationException>(() => springs.AddJacobianProduct(new double[9], new double[9]));
    }

    [Theory]
    [InlineData(3)]
    [InlineData(40)]
    [InlineData(98)]
    public void A_coupling_target_past_the_destination_is_refused_by_name_before_anything_is_written(int bad)
    {
        // 99 couplings: checked several at a time where the runtime has SIMD, the last few one by one; a target out of
        // range in either part is named, with its coupling, and the destination is left as it was.
        var (world, springs) = Chain(100, springs: 99);
        springs.Linearize(world.View(), 1.0, 0.5, new double[world.CoordinateCount]);
        var forward = new int[99];
        var backward = new int[99];
        for (var c = 0; c < 99; c++)
        {
            (forward[c], backward[c]) = (c, 99 + c);
        }

        var destination = new double[9 * 198];
        springs.AddCouplingBlocks(destination, forward, backward);
        Assert.Contains(destination, v => v != 0.0);
        Array.Clear(destination, 0, destination.Length);
        backward[bad] = 198;
        var e = Assert.Throws<ArgumentOutOfRangeException>(() => springs.AddCouplingBlocks(destination, forward, backward));
        Assert.Contains($"Coupling {bad} targets blocks {bad} and 198; the destination holds 198", e.Message, StringComparison.Ordinal);
        Assert.All(destination, v => Assert.Equal(0.0, v));
    }

    public static TheoryData<string> Forces() => new() { "springs", "zero-length", "dampers", "drag" };

    [Theory]
    [MemberData(nameof(Forces))]
    public void A_product_before_any_linearize_throws_a_clear_error(string force)
    {
        // Before: the spring network dereferenced a null pointer (NullReferenceException); the others silently
        // returned a zero Jacobian.
        var (world, _) = Chain(3, springs: 0);
        IForceJacobian jacobian = force switch
        {
            "springs" => WithSpring(new SpringNetwork(world)),
            "zero-length" => WithZeroLengthSpring(new ZeroLengthSprings(world)),
            "dampers" => WithDamper(new Dampers(world)),
            _ => new LinearDrag(0.3),
        };
        var result = new double[9];
        var e = Assert.Throws<InvalidOperationException>(() => jacobian.AddJacobianProduct(Ones(9), result));
        Assert.Contains("Linearize", e.Message, StringComparison.Ordinal);
        Assert.Throws<InvalidOperationException>(() => jacobian.AddDiagonalBlocks(new double[27]));
        Assert.All(result, v => Assert.Equal(0.0, v));
    }

    [Fact]
    public void The_world_refuses_products_before_linearize_and_after_particles_or_forces_change()
    {
        var (world, springs) = Chain(4, springs: 3);
        world.AddForce(springs);
        ILinearizableSystem system = world;
        var n = world.CoordinateCount;
        Assert.Throws<InvalidOperationException>(() => system.AddJacobianProduct(new double[n], new double[n]));

        system.Linearize(0, world.Positions, world.Velocities, 1, 1, UserForceTreatment.Explicit, new double[n]);
        system.AddJacobianProduct(Ones(n), new double[n]);
        system.AddDiagonalBlocks(new double[3 * n]);
        Assert.Throws<ArgumentException>(() => system.AddJacobianProduct(new double[n - 3], new double[n - 3]));

        world.AddParticle(new Vector3d(9, 9, 9), 1);
        var grown = world.CoordinateCount;
        Assert.Throws<InvalidOperationException>(() => system.AddJacobianProduct(new double[grown], new double[grown]));
        Assert.Throws<InvalidOperationException>(() => system.AddDiagonalBlocks(new double[3 * grown]));

        system.Linearize(0, world.Positions, world.Velocities, 1, 1, UserForceTreatment.Explicit, new double[grown]);
        world.AddForce(new LinearDrag(0.1));
        Assert.Throws<InvalidOperationException>(() => system.AddJacobianProduct(new double[grown], new double[grown]));
    }

    [Fact]
    public void A_force_that_adds_a_particle_during_a_bare_evaluate_cannot_make_the_acceleration_loop_write_past_its_buffer()
    {
        var world = new ParticleWorld();
        world.AddParticle(Vector3d.Zero, 1);
        world.AddParticle(new Vector3d(1, 1, 1), 1);
        world.AddForce(new Grower(world));
        var accelerations = new double[9];
        accelerations.AsSpan(6).Fill(12345.0);

        // Before: the loop ran to the grown particle count, writing a fourth and fifth... particle into memory past
        // the six values it was given.
        world.ComputeAccelerations(0, world.Positions, world.Velocities, accelerations.AsSpan(0, 6));
        Assert.Equal(new[] { 12345.0, 12345.0, 12345.0 }, accelerations[6..]);
    }

    [Fact]
    public void A_force_that_changes_the_world_during_a_step_fails_the_step_and_leaves_the_world_as_it_was()
    {
        var world = new ParticleWorld();
        world.AddParticle(Vector3d.Zero, 1);
        world.AddParticle(new Vector3d(1, 1, 1), 1);
        var grower = new Grower(world);
        world.AddForce(grower);
        var before = world.State.ToArray();
        var e = Assert.Throws<InvalidOperationException>(() => world.Step(new RungeKutta4(), 0.01));
        Assert.Contains("during its own step", e.Message, StringComparison.Ordinal);
        Assert.Equal(2, world.Count);
        Assert.Equal(before, world.State.ToArray());
        Assert.Equal(0.0, world.Time);
    }

    private static (ParticleWorld World, SpringNetwork Springs) Chain(int particles, int springs)
    {
        var world = new ParticleWorld(particles);
        for (var i = 0; i < particles; i++)
        {
            world.AddParticle(new Vector3d(0.1 * i, 0.01 * i * i, 0), new Vector3d(0, 0.1 * (i % 3), 0), 1);
        }

        var network = new SpringNetwork(world);
        for (var s = 0; s < springs; s++)
        {
            network.Add(s, s + 1, 10, 0.05, 0.2);
        }

        return (world, network);
    }

    [Fact]
    public void A_user_force_stating_a_coupling_outside_the_world_fails_every_step_not_only_the_first()
    {
        // The multigrid refuses a coupling to a particle that does not exist. It used to mark its hierarchy as built
        // before that check, so the retry found "the same couplings" and ran silently on block Jacobi: a retry that
        // differed from the first attempt.
        var (world, _) = Chain(100, springs: 99);
        world.AddForce(new BadCouplings());
        var implicitEuler = new ImplicitEuler { Preconditioner = ImplicitPreconditioner.Multigrid };
        var before = world.State.ToArray();
        for (var attempt = 0; attempt < 2; attempt++)
        {
            var e = Assert.Throws<InvalidOperationException>(() => world.Step(implicitEuler, 0.01));
            Assert.Contains("joins particles 0 and 100", e.Message, StringComparison.Ordinal);
            Assert.Equal(before, world.State.ToArray());
        }
    }

    [Fact]
    public void The_solvers_pointer_passes_check_their_arrays_where_they_take_the_pointers()
    {
        // Internal passes of implicit Euler: each fixed loop runs over 3 values per particle (9 for blocks). A vector
        // shorter than that is refused where it is bound or passed, instead of being read or written past its end.
        var passes = new ConjugateGradientPasses();
        var masses = new double[] { 1, 1, 1, 1 };
        double[] V(int n) => new double[n];
        Assert.Throws<ArgumentException>(() => passes.Bind(V(12), V(12), V(12), V(12), V(12), V(11), V(12), V(36), masses, masses, null));
        Assert.Throws<ArgumentException>(() => passes.Bind(V(12), V(12), V(12), V(12), V(12), V(12), V(11), V(36), masses, masses, null));
        Assert.Throws<ArgumentException>(() => passes.Bind(V(12), V(12), V(12), V(12), V(12), V(12), V(12), V(35), masses, masses, null));
        passes.Bind(V(12), V(12), V(12), V(12), V(12), V(12), V(12), V(36), masses, masses, null);
        Assert.Throws<ArgumentException>(() => passes.RightHandSide(V(3), 0.1));
        Assert.Throws<ArgumentException>(() => passes.WarmStart(new[] { V(12), V(9) }, new[] { 2.0, -1.0 }, 2));
        Assert.Throws<ArgumentException>(() => passes.WarmStart(new[] { V(12) }, new[] { 2.0, -1.0 }, 2)); // fewer vectors than counted
        Assert.Throws<ArgumentException>(() => passes.WarmStart(new[] { V(12), V(12) }, new[] { 2.0 }, 2)); // fewer coefficients
        Assert.Throws<ArgumentException>(() => passes.WarmStart(new[] { V(12), V(12), V(12), V(12), V(12) }, new double[5], 5)); // past the depth
        Assert.Throws<ArgumentException>(() => passes.WarmStartGram(new[] { V(12) }, new[] { V(9) }, 1, new double[1], new double[1]));
        Assert.Throws<ArgumentException>(() => passes.WarmStartGram(new[] { V(12), V(12) }, new[] { V(12), V(11) }, 2, new double[4], new double[2]));
        Assert.Throws<ArgumentException>(() => passes.WarmStartGram(new[] { V(12), V(12) }, new[] { V(12), V(12) }, 2, new double[3], new double[2]));
        Assert.Throws<ArgumentException>(() => passes.WarmStartGram(new[] { V(12) }, new[] { V(12) }, 0, new double[1], new double[1]));
        Assert.Throws<ArgumentException>(() => passes.SolutionProduct(V(11)));
        Assert.Throws<ArgumentException>(() => passes.EndState(V(12), V(12), V(12), V(11), 0.1));
        Assert.Equal(0.0, passes.RightHandSide(V(12), 0.1)); // bound right, a pass runs: b = 0, b . b = 0

        var (world, _) = Chain(100, springs: 99);
        var multigrid = new AggregationMultigrid();
        var worldMasses = world.Masses.ToArray();
        Assert.Throws<ArgumentException>(() => multigrid.Setup(world, new double[9 * 99], worldMasses, worldMasses, null));
        Assert.Throws<ArgumentException>(() => multigrid.Setup(world, new double[9 * 100], worldMasses, new double[99], null));
    }

    private static SpringNetwork WithSpring(SpringNetwork springs)
    {
        springs.Add(0, 1, 3, 0.5, 0.1);
        return springs;
    }

    private static ZeroLengthSprings WithZeroLengthSpring(ZeroLengthSprings springs)
    {
        springs.Add(0, 2, 3);
        return springs;
    }

    private static Dampers WithDamper(Dampers dampers)
    {
        dampers.Add(1, 2, 0.4);
        return dampers;
    }

    private static double[] Ones(int n)
    {
        var w = new double[n];
        Array.Fill(w, 1.0);
        return w;
    }

    /// <summary>A misbehaving user force: it adds a particle to its world every time it is evaluated.</summary>
    private sealed class Grower : IForceGenerator
    {
        private readonly ParticleWorld _world;

        public Grower(ParticleWorld world)
        {
            _world = world;
        }

        public void AddForces(in ParticleState state, Span<double> forces) => _world.AddParticle(new Vector3d(5, 5, 5), 1);
    }

    /// <summary>A user force with a (zero) Jacobian that states one coupling to a particle past the world's last.</summary>
    private sealed class BadCouplings : IForceGenerator, IJacobianCouplings
    {
        public int CouplingCount => 1;

        public void AddForces(in ParticleState state, Span<double> forces)
        {
        }

        public void Linearize(in ParticleState state, double positionScale, double velocityScale, Span<double> positionJacobianTimesVelocity)
        {
        }

        public void AddJacobianProduct(ReadOnlySpan<double> w, Span<double> result)
        {
        }

        public void AddDiagonalBlocks(Span<double> blocks)
        {
        }

        public void WriteCouplings(Span<int> first, Span<int> second)
        {
            first[0] = 0;
            second[0] = 100;
        }

        public void AddCouplingBlocks(Span<double> destination, ReadOnlySpan<int> forwardBlock, ReadOnlySpan<int> backwardBlock)
        {
        }
    }
}
