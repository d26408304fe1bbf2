using System;
using ParticlePhysics.Internal;
using ParticlePhysics.Numerics;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Integrators.Multigrid;

/// <summary>
/// The preconditioner of implicit Euler's conjugate gradients on large systems: a two-level additive method whose
/// coarse level is an aggregation multigrid V-cycle, built from the couplings the forces state
/// (<see cref="ILinearizableSystem.CouplingCount"/>), so that it knows nothing of cloths or grids.
/// </summary>
/// <remarks>
/// Block Jacobi, the 3 x 3 diagonal blocks of A = M - J, damps short wavelengths only: on a stiff cloth the
/// iterations needed grow with its width. Here z = D^-1 r + P B_c P^T r, with P the piecewise-constant prolongation
/// from aggregates of particles (pairwise matchings, twice per level, by the number of couplings between groups: a
/// function of the topology alone, so that a restored run rebuilds the same preconditioner) and B_c one V-cycle on
/// the Galerkin operator A_c = P^T A P. For piecewise-constant P the Galerkin sum is cheap: A_c[I, J] is the sum of
/// the blocks A_ij with i in I and j in J (couplings inside an aggregate land on its diagonal), and the coarse
/// operator again has the form mass + pair terms, so the same construction recurses. The V-cycle smooths with one
/// block-Jacobi sweep before and after the coarse correction; on an operator of that form
/// x^T A x &lt;= 2 x^T D x - x^T M x, so lambda_max(D^-1 A) &lt; 2 and the sweep converges, which keeps B_c, and
/// so the preconditioner, symmetric positive definite. The coarsest level (at most 16 aggregates) is solved by a
/// dense Cholesky factorisation. Additive rather than multiplicative at the top: a multiplicative cycle needs two
/// more products with the fine operator per iteration, more than its fewer iterations save (docs/benchmarks.md,
/// "Implicit Euler's preconditioner"). Pinned particles are filtered: they take no part in the
/// restriction, the prolongation or the Galerkin sums, which therefore follow pinning without a rebuild.
/// Every pass runs in fixed chunks whose partial sums are combined in chunk order, so the result does not depend
/// on how many threads run them.
/// <para>Where each job lives: this file holds the setup, the entry points the solver calls and the V-cycle;
/// AggregationMultigrid.Hierarchy.cs builds the levels from the couplings with <see cref="CouplingGraph"/>'s
/// matchings; <see cref="FineGalerkinAssembly"/> and <see cref="CoarseGalerkinPass"/> make the Galerkin operators;
/// <see cref="CoarseLevel"/> stores a level and applies its rows, and its passes are
/// <see cref="BlockInversionPass"/>, <see cref="ResidualRestrictionPass"/> and <see cref="PostSmoothingPass"/>; the
/// fine level's passes are <see cref="RestrictionPass"/>, <see cref="UpdateAndRestrictionPass"/> and
/// <see cref="PostSmoothAndProlongPass"/>; <see cref="CoarsestSolver"/> solves the last level directly.</para>
/// </remarks>
internal sealed unsafe partial class AggregationMultigrid
{
    /// <summary>The chunks of every fine-level pass, and so the order of every sum: never the thread count.</summary>
    public const int Chunks = 16;

    /// <summary>The most aggregates of the coarsest level, which is solved directly.</summary>
    public const int CoarsestNodes = 16;
    private const int MaxLevels = 12;

    private readonly RestrictionPass _restriction = new();
    private readonly UpdateAndRestrictionPass _updateAndRestriction = new();
    private readonly PostSmoothAndProlongPass _postSmoothAndProlong = new();
    private readonly BlockInversionPass _inversion = new();
    private readonly CoarseGalerkinPass _galerkin = new();
    private readonly ResidualRestrictionPass _residualRestriction = new();
    private readonly PostSmoothingPass _postSmoothing = new();
    private readonly CoarsestSolver _coarsest = new();

    // The topology the hierarchy was built for.
    private int[] _first = Array.Empty<int>();
    private int[] _second = Array.Empty<int>();
    private int[] _checkFirst = Array.Empty<int>();
    private int[] _checkSecond = Array.Empty<int>();
    private int _couplings = -1;
    private long? _revision; // the system's coupling revision when the couplings were last seen, if it has one
    private int _particles = -1;

    // Fine level: the aggregate of each particle and the members of each aggregate.
    private readonly FineGalerkinAssembly _fineAssembly = new();
    private int[] _aggregate = Array.Empty<int>();
    private int[] _memberStart = Array.Empty<int>();
    private int[] _members = Array.Empty<int>();
    private int[] _chunkMembers = Array.Empty<int>(); // per fine chunk: [first, end) of its members when contiguous, else -1, -1
    private CoarseLevel[] _levels = Array.Empty<CoarseLevel>();

    /// <summary>True when there is a coarse level (else the preconditioner is block Jacobi alone).</summary>
    public bool HasCoarseLevels => _levels.Length > 0;

    /// <summary>The number of aggregates on each coarse level, for diagnostics and tests.</summary>
    public int[] LevelSizes()
    {
        var sizes = new int[_levels.Length];
        for (var l = 0; l < sizes.Length; l++)
        {
            sizes[l] = _levels[l].Count;
        }

        return sizes;
    }

    /// <summary>
    /// For tests: the map of level <paramref name="level"/>'s rows into the coarse level's, as built (level 0 is the
    /// first coarse level: the map from the particles into it; level l the map from level l - 1's aggregates).
    /// </summary>
    internal int[] AggregateMap(int level) => level == 0 ? _aggregate : _levels[level - 1].NextAggregate;

    /// <summary>
    /// For tests: coarse level <paramref name="level"/>'s operator as a dense row-major matrix of 3 Count values a
    /// side, read from its blocks as the sweeps read them (a block left of the diagonal transposed from its mirror).
    /// </summary>
    internal double[] DenseOperator(int level) => _levels[level].Dense();

    /// <summary>
    /// Rebuilds the hierarchy if the couplings changed, then the coarse operators from the system's current
    /// linearisation: <paramref name="fineDiagonal"/> holds J_ii (9 values per particle, as the forces added them).
    /// </summary>
    public void Setup(ILinearizableSystem system, double[] fineDiagonal, Span<double> masses, Span<double> inverseMasses, IParallelRunner? runner)
    {
        var particles = masses.Length;
        if (inverseMasses.Length != particles || fineDiagonal.Length < 9L * particles)
        {
            throw new ArgumentException(
                $"The multigrid needs 9 diagonal values and one inverse mass per particle, for {particles} particles.");
        }

        // The couplings are compared pair by pair unless the system can tell that they are the same (ICouplingRevision).
        var count = system.CouplingCount;
        var revised = system is ICouplingRevision r && r.TryGetCouplingRevision(out var revision) ? revision : (long?)null;
        var unchanged = revised is not null && revised == _revision;
        if (count != _couplings || particles != _particles || (!unchanged && !SameCouplings(system, count)))
        {
            Build(system, count, particles);
        }

        _revision = revised;

        if (_levels.Length == 0)
        {
            return;
        }

        _fineAssembly.Assemble(system, fineDiagonal, masses, inverseMasses, count, _levels[0], _memberStart, _members, runner);
        for (var l = 0; l < _levels.Length; l++)
        {
            var level = _levels[l];
            _inversion.Set(level);
            Run(level.RunnerFor(runner), _inversion);
            if (l + 1 < _levels.Length)
            {
                _galerkin.Set(level, _levels[l + 1]);
                Run(level.RunnerFor(runner), _galerkin);
            }
            else
            {
                _coarsest.Factor(level);
            }
        }
    }

    /// <summary>
    /// The first half of z = D^-1 r + P B_c P^T r on its own (the solve's first preconditioning): B_1 = P^T r over the
    /// free particles, and level 1's pre-smoothing from zero, X_1 = D_1^-1 B_1.
    /// </summary>
    public void Restrict(double[] residual, double[] inverseMasses, IParallelRunner? runner)
    {
        var first = CheckBound(residual, inverseMasses);
        fixed (double* r = residual, w = inverseMasses)
        fixed (int* memberStart = _memberStart, members = _members)
        fixed (double* coarseB = first.B, coarseX = first.X, coarseInverse = first.Inverse)
        {
            _restriction.Set(r, w, memberStart, members, first.Count, coarseB, coarseInverse, coarseX, smoothed: _levels.Length > 1);
            Run(runner, _restriction);
        }
    }

    /// <summary>
    /// One iteration's update of the conjugate gradients (<see cref="ConjugateGradientUpdate"/>: p, s, dv and r, and
    /// jw cleared) fused with <see cref="Restrict"/> of the new r, in one pass over the aggregates' members: the
    /// restriction reads r while the update has it in the cache, and an iteration hands off once less. Returns r . r
    /// after the update, summed in chunk order.
    /// </summary>
    public double UpdateAndRestrict(
        double[] preconditioned, double[] jacobianProduct, double[] masses, double[] coordinateMasses, double[] direction,
        double[] directionProduct, double[] solution, double[] residual, double[] inverseMasses, double alpha, double beta,
        IParallelRunner? runner)
    {
        var first = CheckBound(residual, inverseMasses);
        var n = 3L * _particles;
        if (preconditioned.Length < n || jacobianProduct.Length < n || coordinateMasses.Length < n || direction.Length < n
            || directionProduct.Length < n || solution.Length < n || masses.Length < _particles)
        {
            throw Shorter();
        }

        fixed (double* z = preconditioned, jw = jacobianProduct, m = masses, mc = coordinateMasses, p = direction)
        fixed (double* s = directionProduct, dv = solution, r = residual, w = inverseMasses)
        fixed (int* memberStart = _memberStart, members = _members, chunkMembers = _chunkMembers)
        fixed (double* coarseB = first.B, coarseX = first.X, coarseInverse = first.Inverse)
        {
            _updateAndRestriction.Set(z, jw, m, mc, alpha, beta, p, s, dv, r, w);
            _updateAndRestriction.SetAggregates(memberStart, members, chunkMembers, first.Count, coarseB, coarseInverse, coarseX, smoothed: _levels.Length > 1);
            Run(runner, _updateAndRestriction);
        }

        return _updateAndRestriction.Sum();
    }

    /// <summary>
    /// The second half of z = D^-1 r + P B_c P^T r: the V-cycle below level 1, then level 1's post-smoothing fused with
    /// the fine level's z = D^-1 r + P X_1 (zero on pinned particles; D^-1 as the packed upper triangles of
    /// <paramref name="inverses"/>). Returns r . z, summed in chunk order.
    /// </summary>
    public double CycleAndProlong(double[] residual, double[] inverses, double[] inverseMasses, double[] preconditioned, IParallelRunner? runner)
    {
        var first = CheckBound(residual, inverseMasses);
        if (preconditioned.Length < 3L * _particles || inverses.Length < 6L * _particles)
        {
            throw Shorter();
        }

        Cycle(0, runner);
        var smoothed = _levels.Length > 1;
        fixed (double* r = residual, inverse = inverses, w = inverseMasses, z = preconditioned)
        fixed (int* memberStart = _memberStart, members = _members)
        fixed (double* x = smoothed ? first.Smoothed : first.X)
        {
            _postSmoothAndProlong.Set(r, inverse, w, memberStart, members, first.Count, smoothed ? first : null, x, z);
            Run(runner, _postSmoothAndProlong);
        }

        if (smoothed)
        {
            first.SwapSmoothed();
        }

        return _postSmoothAndProlong.Sum();
    }

    /// <summary>The first level, after checking that r and the inverse masses cover the hierarchy's particles.</summary>
    private CoarseLevel CheckBound(double[] residual, double[] inverseMasses)
    {
        // The fine passes run their pointers over the particles of the hierarchy: every array must cover them.
        if (_levels.Length == 0 || residual.Length < 3L * _particles || inverseMasses.Length < _particles)
        {
            throw Shorter();
        }

        return _levels[0];
    }

    private InvalidOperationException Shorter() => new(
        $"The multigrid was set up for {_particles} particles; it was applied before any coarse level was built, or to vectors shorter than theirs.");

    private static void Run(IParallelRunner? runner, IParallelWork work) => Chunk.RunAll(runner, work, Chunks);

    /// <summary>
    /// One V-cycle on coarse level l, X ~ A_l^-1 B, from a level whose pre-smoothing from zero, X = D^-1 B, is done (the
    /// pass above it did it as it restricted): the residual restricted to the next level (and the next level's own
    /// pre-smoothing) in one pass, the cycle below, which ends with the prolongation X += P X_next, then the
    /// post-smoothing X += D^-1 (B - A X) in one pass, which adds each row's new X to its members on the level above
    /// (that level's prolongation: each row of the level above belongs to one aggregate, so the rows of a pass write
    /// disjoint members). Below the coarsest level's solve the prolongation is a loop of its own on the calling thread
    /// (three additions per row). Level 1's post-smoothing is left to <see cref="CycleAndProlong"/>, which fuses it with
    /// the fine level.
    /// </summary>
    private void Cycle(int l, IParallelRunner? runner)
    {
        var level = _levels[l];
        if (l == _levels.Length - 1)
        {
            _coarsest.Solve(level);
            return;
        }

        var next = _levels[l + 1];
        _residualRestriction.Set(level, next, smoothNext: l + 2 < _levels.Length);
        Run(level.RunnerFor(runner), _residualRestriction);
        Cycle(l + 1, runner);
        if (l + 1 == _levels.Length - 1)
        {
            level.Prolong(next);
        }

        if (l > 0)
        {
            _postSmoothing.Set(level, _levels[l - 1]);
            Run(level.RunnerFor(runner), _postSmoothing);
            level.SwapSmoothed();
        }
    }
}
