using System;
using System.Linq;
using ParticlePhysics.Cloth;
using ParticlePhysics.Integrators;
using ParticlePhysics.Integrators.Multigrid;
using ParticlePhysics.Numerics;
using ParticlePhysics.Parallel;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Implicit;

/// <summary>
/// Implicit Euler's start from the last steps (<see cref="WarmStartHistory"/>) and the solver pieces beside it: what
/// the state holds under each preconditioner and across a switch, a history whose steps are all alike (the singular
/// Galerkin system), a change of size, pinned particles of infinite mass, the coarse operators against P^T A P, and
/// the packed inversion against the full one.
/// </summary>
public class WarmStartTests
{
    private const double Frame = 1.0 / 60;

    [Fact]
    public void Block_jacobi_keeps_the_two_steps_it_extrapolates_and_the_multigrid_four_with_their_products()
    {
        var world = Cloth(16);
        var n = world.CoordinateCount;
        var implicitEuler = new ImplicitEuler { Tolerance = 1e-3, Preconditioner = ImplicitPreconditioner.BlockJacobi };
        StateMetrics.Run(world, implicitEuler, Frame, 5);
        Assert.Equal(1 + (2 * n), implicitEuler.StateLength);
        Assert.Equal(2.0, Written(implicitEuler)[0]); // two steps, no products: the header as the older library wrote it

        implicitEuler.Preconditioner = ImplicitPreconditioner.Multigrid;
        StateMetrics.Run(world, implicitEuler, Frame, 1);
        Assert.Equal(16.0 + 3 + 8, Written(implicitEuler)[0]); // three steps, the newest with its product
        StateMetrics.Run(world, implicitEuler, Frame, 3);
        Assert.Equal(16.0 + 4 + 32, Written(implicitEuler)[0]); // four, all with products

        // One block-Jacobi step: two steps known again, without products.
        implicitEuler.Preconditioner = ImplicitPreconditioner.BlockJacobi;
        StateMetrics.Run(world, implicitEuler, Frame, 1);
        Assert.Equal(2.0, Written(implicitEuler)[0]);
        Assert.Equal(1 + (2 * n), implicitEuler.StateLength);
    }

    [Fact]
    public void A_state_with_fewer_products_than_steps_restores_a_run_bit_for_bit()
    {
        var world = Cloth(16);
        var implicitEuler = new ImplicitEuler { Tolerance = 1e-3, Preconditioner = ImplicitPreconditioner.BlockJacobi };
        StateMetrics.Run(world, implicitEuler, Frame, 3);
        implicitEuler.Preconditioner = ImplicitPreconditioner.Multigrid;
        StateMetrics.Run(world, implicitEuler, Frame, 2);
        var state = Written(implicitEuler);
        Assert.Equal(16.0 + 4 + 16, state[0]); // four steps, the two newest with products
        var atSave = world.State.ToArray();
        var time = world.Time;
        StateMetrics.Run(world, implicitEuler, Frame, 4);

        var restored = Cloth(16);
        restored.SetState(atSave);
        restored.Time = time;
        var fresh = new ImplicitEuler { Tolerance = 1e-3 };
        fresh.ReadState(state);
        StateMetrics.Run(restored, fresh, Frame, 4);
        Assert.Equal(StateMetrics.BitHash(world.State), StateMetrics.BitHash(restored.State));
    }

    [Fact]
    public void Steps_that_are_all_alike_make_a_singular_start_system_and_the_start_falls_back_to_fewer_steps()
    {
        // A free cloth at rest length without drag or damping falls as one body: every step's dv is the same, g h on
        // every particle, so the Galerkin system of the last four steps has rank one. The start must drop steps until
        // it is regular (one step: the exact dv), not divide by a zero pivot.
        var world = new ClothScenario { Resolution = 1.0 / 15, Pinning = ClothPinning.None, Drag = 0, Damping = 0 }.Build();
        var implicitEuler = new ImplicitEuler { Tolerance = 1e-6 };
        for (var step = 1; step <= 12; step++)
        {
            world.Step(implicitEuler, Frame);
            Assert.True(implicitEuler.LastConverged, $"step {step}");
            if (step > 4)
            {
                Assert.True(implicitEuler.LastIterations <= 1, $"step {step}: {implicitEuler.LastIterations} iterations");
            }
        }

        // Backward Euler in free fall: v = -g t exactly, up to the springs' rounding.
        for (var i = 0; i < world.Count; i++)
        {
            var v = world.GetVelocity(i);
            Assert.Equal(-ParticlePhysics.Forces.Gravity.StandardAcceleration * 12 * Frame, v.Y, 1e-9);
            Assert.Equal(0.0, v.X, 1e-9);
            Assert.Equal(0.0, v.Z, 1e-9);
        }
    }

    [Fact]
    public void A_world_that_grows_between_steps_starts_the_next_solve_cold_and_keeps_its_new_size()
    {
        var world = Cloth(16);
        var implicitEuler = new ImplicitEuler { Tolerance = 1e-3 };
        StateMetrics.Run(world, implicitEuler, Frame, 5);
        world.AddParticle(new Vector3d(0.5, 1, 0.5), 0.01);
        var n = world.CoordinateCount;
        world.Step(implicitEuler, Frame);
        Assert.True(implicitEuler.LastConverged);
        Assert.Equal(1 + (2 * n), implicitEuler.StateLength); // one step known, with its product, at the new size
        StateMetrics.Run(world, implicitEuler, Frame, 4);
        Assert.Equal(1 + (8 * n), implicitEuler.StateLength);
        Assert.All(world.State.ToArray(), value => Assert.True(double.IsFinite(value)));
    }

    [Theory]
    [InlineData(ImplicitPreconditioner.BlockJacobi)]
    [InlineData(ImplicitPreconditioner.Multigrid)]
    public void A_system_that_gives_pinned_particles_infinite_mass_steps_as_the_world_does(ImplicitPreconditioner preconditioner)
    {
        // Pinned particles take no part in the solve, whatever mass a system reports for them (ParticleWorld reports
        // the mass it was given; another system may well say infinity). The update computes w = M z - J z on every
        // particle, so an infinite mass there must not make a NaN.
        var world = Cloth(16);
        for (var step = 0; step < 3; step++)
        {
            var state = world.State.ToArray();
            var byWorld = new double[state.Length];
            var byWrapper = new double[state.Length];
            new ImplicitEuler { Preconditioner = preconditioner, Tolerance = 1e-6 }.Step(world, world.Time, state, byWorld, Frame);
            var implicitEuler = new ImplicitEuler { Preconditioner = preconditioner, Tolerance = 1e-6 };
            implicitEuler.Step(new InfinitePinnedMass(world), world.Time, state, byWrapper, Frame);
            Assert.True(implicitEuler.LastConverged);
            Assert.Equal(StateMetrics.BitHash(byWorld), StateMetrics.BitHash(byWrapper));
            world.Step(new ImplicitEuler { Preconditioner = preconditioner, Tolerance = 1e-6 }, Frame);
        }
    }

    [Fact]
    public void The_coarse_operators_are_the_galerkin_products_of_the_fine_one()
    {
        // Level 1 = P^T A P with A = M - J on the free particles and P the piecewise-constant prolongation from the
        // aggregates; each level below from the one above the same way. Built densely here from J's products with unit
        // vectors, against the blocks the sweeps read (those left of the diagonal transposed from their mirrors).
        var world = Cloth(12);
        world.Step(new ImplicitEuler { Tolerance = 1e-6 }, Frame); // a hanging, stretched cloth: J has both terms
        ILinearizableSystem system = world;
        var n = system.CoordinateCount;
        var particles = n / 3;
        var x = world.State.Slice(0, n).ToArray();
        var v = world.State.Slice(n, n).ToArray();
        var blocks = new double[3 * n];
        system.AccumulateForcesAndLinearize(world.Time, x, v, Frame * Frame, Frame, UserForceTreatment.Explicit, new double[n], blocks);
        var masses = world.Masses.ToArray();
        var inverseMasses = world.InverseMasses.ToArray();
        var multigrid = new AggregationMultigrid();
        multigrid.Setup(system, blocks, masses, inverseMasses, null);
        Assert.True(multigrid.HasCoarseLevels);

        var fine = new double[n, n]; // A = M - J, rows and columns of pinned particles left 0
        for (var c = 0; c < n; c++)
        {
            var unit = new double[n];
            unit[c] = 1.0;
            var column = new double[n];
            system.AddJacobianProduct(unit, column);
            for (var r = 0; r < n; r++)
            {
                var free = inverseMasses[r / 3] != 0.0 && inverseMasses[c / 3] != 0.0;
                fine[r, c] = free ? (r == c ? masses[r / 3] : 0.0) - column[r] : 0.0;
            }
        }

        var expected = Galerkin(fine, multigrid.AggregateMap(0), multigrid.LevelSizes()[0]);
        for (var level = 0; level < multigrid.LevelSizes().Length; level++)
        {
            var size = 3 * multigrid.LevelSizes()[level];
            var actual = multigrid.DenseOperator(level);
            var scale = 0.0;
            for (var r = 0; r < size; r++)
            {
                scale = Math.Max(scale, Math.Abs(expected[r, r]));
            }

            for (var r = 0; r < size; r++)
            {
                for (var c = 0; c < size; c++)
                {
                    Assert.True(
                        Math.Abs(actual[(r * size) + c] - expected[r, c]) <= 1e-12 * scale,
                        $"level {level + 1}, ({r}, {c}): {actual[(r * size) + c]} against {expected[r, c]}");
                }
            }

            if (level + 1 < multigrid.LevelSizes().Length)
            {
                var dense = new double[size, size];
                for (var r = 0; r < size; r++)
                {
                    for (var c = 0; c < size; c++)
                    {
                        dense[r, c] = actual[(r * size) + c];
                    }
                }

                expected = Galerkin(dense, multigrid.AggregateMap(level + 1), multigrid.LevelSizes()[level + 1]);
            }
        }

        Assert.True(multigrid.LevelSizes().Length >= 2, $"{multigrid.LevelSizes().Length} coarse levels for {particles} particles");
    }

    [Fact]
    public void The_packed_inverse_of_a_symmetric_block_has_the_bits_of_the_full_inverse()
    {
        // InvertBlocks inverts M_i - J_ii from its upper triangle; the full cofactor inversion of the same symmetric
        // block gives the same values to the last bit (each mirrored cofactor is the same two products).
        var random = new SeededRandom(20261202);
        const int particles = 200;
        var masses = new double[particles];
        var inverseMasses = new double[particles];
        var blocks = new double[9 * particles];
        for (var i = 0; i < particles; i++)
        {
            masses[i] = 0.01 + random.NextDouble();
            inverseMasses[i] = i % 17 == 0 ? 0.0 : 1.0 / masses[i];
            for (var p = 0; p < 3; p++)
            {
                for (var q = p; q < 3; q++)
                {
                    var value = (random.NextDouble() - 0.5) * (p == q ? 0.5 : 0.2) * masses[i];
                    blocks[(9 * i) + (3 * p) + q] = value;
                    blocks[(9 * i) + (3 * q) + p] = value;
                }
            }
        }

        double[] V() => new double[3 * particles];
        var passes = new ConjugateGradientPasses();
        passes.Bind(V(), V(), V(), V(), V(), V(), V(), blocks, masses, inverseMasses, null);
        passes.InvertBlocks();
        var full = new double[9];
        var inverse = new double[9];
        for (var i = 0; i < particles; i++)
        {
            var packed = passes.Inverses.AsSpan(6 * i, 6).ToArray();
            if (inverseMasses[i] == 0.0)
            {
                Assert.All(packed, value => Assert.Equal(0.0, value));
                continue;
            }

            for (var k = 0; k < 9; k++)
            {
                full[k] = -blocks[(9 * i) + k];
            }

            full[0] += masses[i];
            full[4] += masses[i];
            full[8] += masses[i];
            Assert.True(Blocks3.Invert(full, 0, inverse, 0));
            var upper = new[] { inverse[0], inverse[1], inverse[2], inverse[4], inverse[5], inverse[8] };
            Assert.Equal(upper.Select(BitConverter.DoubleToInt64Bits), packed.Select(BitConverter.DoubleToInt64Bits));
        }
    }

    [Fact]
    public void The_integrator_state_bound_is_1024_plus_24_values_a_particle_and_saturates()
    {
        Assert.Equal(1024, IntegratorStateLimit.MaxLength(0));
        Assert.Equal(1024, IntegratorStateLimit.MaxLength(-3));
        Assert.Equal(1024 + (24 * 4096), IntegratorStateLimit.MaxLength(4096));
        Assert.Equal(int.MaxValue, IntegratorStateLimit.MaxLength(int.MaxValue));
        Assert.Equal(IntegratorStateLimit.MaxLength(4096), ParticlePhysics.Snapshots.SimulationSnapshot.MaxIntegratorStateLength(4096));
    }

    private static double[,] Galerkin(double[,] a, int[] map, int groups)
    {
        var coarse = new double[3 * groups, 3 * groups];
        var size = a.GetLength(0);
        for (var r = 0; r < size; r++)
        {
            for (var c = 0; c < size; c++)
            {
                coarse[(3 * map[r / 3]) + (r % 3), (3 * map[c / 3]) + (c % 3)] += a[r, c];
            }
        }

        return coarse;
    }

    private static ParticleWorld Cloth(int side) => new ClothScenario { Resolution = 1.0 / (side - 1) }.Build();

    private static double[] Written(ImplicitEuler integrator)
    {
        var state = new double[integrator.StateLength];
        integrator.WriteState(state);
        return state;
    }

    /// <summary>A particle world that reports its pinned particles' masses as infinite (their inverse masses stay 0).</summary>
    private sealed class InfinitePinnedMass : ILinearizableSystem
    {
        private readonly ILinearizableSystem _world;
        private readonly double[] _masses;

        public InfinitePinnedMass(ParticleWorld world)
        {
            _world = world;
            _masses = world.Masses.ToArray();
            for (var i = 0; i < _masses.Length; i++)
            {
                if (world.InverseMasses[i] == 0.0)
                {
                    _masses[i] = double.PositiveInfinity;
                }
            }
        }

        public ReadOnlySpan<double> Masses => _masses;

        public ReadOnlySpan<double> InverseMasses => _world.InverseMasses;

        public int Dimension => _world.Dimension;

        public int CoordinateCount => _world.CoordinateCount;

        public int CouplingCount => _world.CouplingCount;

        public IParallelRunner? Runner => _world.Runner;

        public void Evaluate(double t, ReadOnlySpan<double> state, Span<double> derivative) => _world.Evaluate(t, state, derivative);

        public void ComputeAccelerations(double t, ReadOnlySpan<double> x, ReadOnlySpan<double> v, Span<double> a) =>
            _world.ComputeAccelerations(t, x, v, a);

        public ReadOnlySpan<double> AccumulateForces(double t, ReadOnlySpan<double> x, ReadOnlySpan<double> v) => _world.AccumulateForces(t, x, v);

        public void Linearize(double t, ReadOnlySpan<double> x, ReadOnlySpan<double> v, double a, double b, UserForceTreatment u, Span<double> jv) =>
            _world.Linearize(t, x, v, a, b, u, jv);

        public ReadOnlySpan<double> AccumulateForcesAndLinearize(
            double t, ReadOnlySpan<double> x, ReadOnlySpan<double> v, double a, double b, UserForceTreatment u, Span<double> jv, Span<double> blocks) =>
            _world.AccumulateForcesAndLinearize(t, x, v, a, b, u, jv, blocks);

        public void AddJacobianProduct(ReadOnlySpan<double> w, Span<double> result) => _world.AddJacobianProduct(w, result);

        public void AddDiagonalBlocks(Span<double> blocks) => _world.AddDiagonalBlocks(blocks);

        public void WriteCouplings(Span<int> first, Span<int> second) => _world.WriteCouplings(first, second);

        public void AddCouplingBlocks(Span<double> destination, ReadOnlySpan<int> forwardBlock, ReadOnlySpan<int> backwardBlock) =>
            _world.AddCouplingBlocks(destination, forwardBlock, backwardBlock);
    }
}
