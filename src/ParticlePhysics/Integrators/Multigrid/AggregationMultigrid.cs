using System;
using System.Collections.Generic;
using System.Numerics;
using System.Runtime.CompilerServices;
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
/// more products with the fine operator per iteration, and measured on the 64 x 64 cloth the additive form costs
/// fewer fine products per step (docs/benchmarks.md). Pinned particles are filtered: they take no part in the
/// restriction, the prolongation or the Galerkin sums, which therefore follow pinning without a rebuild.
/// Every pass runs in fixed chunks whose partial sums are combined in chunk order, so the result does not depend
/// on how many threads run them.
/// </remarks>
internal sealed unsafe class AggregationMultigrid
{
    /// <summary>The chunks of every fine-level pass, and so the order of every sum: never the thread count.</summary>
    public const int Chunks = 16;

    private const int CoarsestNodes = 16;
    private const int MaxLevels = 12;

    private readonly RestrictionPass _restriction = new();
    private readonly UpdateAndRestrictionPass _updateAndRestriction = new();
    private readonly PostSmoothAndProlongPass _postSmoothAndProlong = new();

    // The topology the hierarchy was built for.
    private int[] _first = Array.Empty<int>();
    private int[] _second = Array.Empty<int>();
    private int[] _checkFirst = Array.Empty<int>();
    private int[] _checkSecond = Array.Empty<int>();
    private int _couplings = -1;
    private long? _revision; // the system's coupling revision when the couplings were last seen, if it has one
    private int _particles = -1;

    // Fine level: the aggregate of each particle, its members, and the block
    // of level 1 that each fine coupling's A_ij (forward) and A_ji (backward) land in (-1: none, or not the direction stored).
    private readonly AssemblyPass _assembly = new();
    // The level-1 targets of each part of the assembly, forward then backward: for one part, for the runner's parts,
    // and the set in use.
    private int[][] _whole = Array.Empty<int[]>();
    private int[][] _parted = Array.Empty<int[]>();
    private int[][] _targets = Array.Empty<int[]>();
    private bool[] _filteredFor = Array.Empty<bool>(); // the pinned particles the filtered targets were made for
    private int[] _aggregate = Array.Empty<int>();
    private int[] _memberStart = Array.Empty<int>();
    private int[] _members = Array.Empty<int>();
    private int[] _chunkMembers = Array.Empty<int>(); // per fine chunk: [first, end) of its members when contiguous, else -1, -1
    private int[] _forwardTarget = Array.Empty<int>();
    private int[] _backwardTarget = Array.Empty<int>();
    private Level[] _levels = Array.Empty<Level>();

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

        GalerkinFromFine(system, fineDiagonal, masses, inverseMasses, count, runner);
        for (var l = 0; l < _levels.Length; l++)
        {
            var level = _levels[l];
            level.Invert(runner);
            if (l + 1 < _levels.Length)
            {
                level.GalerkinInto(_levels[l + 1], runner);
            }
            else
            {
                level.FactorDense();
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
    private Level CheckBound(double[] residual, double[] inverseMasses)
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
            level.SolveCoarsest();
            return;
        }

        var next = _levels[l + 1];
        level.RestrictResidual(next, smoothNext: l + 2 < _levels.Length, runner);
        Cycle(l + 1, runner);
        if (l + 1 == _levels.Length - 1)
        {
            level.Prolong(next);
        }

        if (l > 0)
        {
            level.PostSmooth(next, _levels[l - 1], runner);
        }
    }

    private bool SameCouplings(ILinearizableSystem system, int count)
    {
        if (_checkFirst.Length < count)
        {
            _checkFirst = new int[count];
            _checkSecond = new int[count];
        }

        system.WriteCouplings(_checkFirst.AsSpan(0, count), _checkSecond.AsSpan(0, count));
        return _checkFirst.AsSpan(0, count).SequenceEqual(_first.AsSpan(0, count))
            && _checkSecond.AsSpan(0, count).SequenceEqual(_second.AsSpan(0, count));
    }

    /// <summary>
    /// The level-1 operator: the fine diagonal blocks M - J_ii and the coupling blocks -J_ij summed per aggregate.
    /// The forces add their J_ij straight into the aggregates' blocks (<see cref="ILinearizableSystem.AddCouplingBlocks"/>),
    /// so a block holds -A_1 until its sign is turned at the end. On a runner, each part assembles the block rows of a
    /// range of aggregates, with the targets outside it masked: every block still gets its terms in the same order.
    /// </summary>
    private void GalerkinFromFine(
        ILinearizableSystem system, double[] fineDiagonal, Span<double> masses, Span<double> inverseMasses, int count, IParallelRunner? runner)
    {
        var parts = runner is { MaxParallelism: > 1 } ? runner.MaxParallelism : 1;
        FilterTargets(inverseMasses, count, parts);
        fixed (double* fine = fineDiagonal, m = masses, w = inverseMasses)
        {
            _assembly.Set(this, system, fine, m, w, count);
            if (parts > 1)
            {
                runner!.Run(_assembly, parts);
            }
            else
            {
                _assembly.Execute(0, 1);
            }
        }
    }

    /// <summary>
    /// The level-1 targets of the couplings for each of <paramref name="parts"/> ranges of aggregates, without
    /// couplings that touch a pinned particle (rebuilt when pinning, the topology or the parts change).
    /// </summary>
    private void FilterTargets(Span<double> inverseMasses, int count, int parts)
    {
        var same = _filteredFor.Length == _particles;
        for (var i = 0; same && i < _particles; i++)
        {
            same = _filteredFor[i] == (inverseMasses[i] == 0.0);
        }

        if (!same)
        {
            _filteredFor = new bool[_particles];
            for (var i = 0; i < _particles; i++)
            {
                _filteredFor[i] = inverseMasses[i] == 0.0;
            }

            _whole = Array.Empty<int[]>();
            _parted = Array.Empty<int[]>();
        }

        // One set of targets for the calling thread alone and one for the runner's parts, so that a host switching
        // between them does not rebuild (and allocate) at every switch.
        ref var targets = ref parts == 1 ? ref _whole : ref _parted;
        if (targets.Length != 2 * parts)
        {
            targets = FilteredTargets(count, parts);
        }

        _targets = targets;
    }

    private int[][] FilteredTargets(int count, int parts)
    {
        var level = _levels[0];
        var targets = new int[2 * parts][];
        for (var part = 0; part < parts; part++)
        {
            var (begin, end) = Chunk.Range(part, parts, level.Count);
            var forward = targets[2 * part] = new int[count];
            var backward = targets[(2 * part) + 1] = new int[count];
            for (var e = 0; e < count; e++)
            {
                // (Both targets -1: a coupling of a particle with itself; one: the block stored is the other direction's.)
                var skip = (_forwardTarget[e] < 0 && _backwardTarget[e] < 0) || _filteredFor[_first[e]] || _filteredFor[_second[e]];
                forward[e] = !skip && level.InRows(_forwardTarget[e], begin, end) ? _forwardTarget[e] : -1;
                backward[e] = !skip && level.InRows(_backwardTarget[e], begin, end) ? _backwardTarget[e] : -1;
            }
        }

        return targets;
    }

    /// <summary>One part of the level-1 assembly: the block rows of a range of aggregates.</summary>
    private sealed class AssemblyPass : IParallelWork
    {
        private AggregationMultigrid? _owner;
        private ILinearizableSystem? _system;
        private double* _fine;
        private double* _masses;
        private double* _inverseMasses;
        private int _count;

        public void Set(AggregationMultigrid owner, ILinearizableSystem system, double* fine, double* masses, double* inverseMasses, int count)
        {
            _owner = owner;
            _system = system;
            _fine = fine;
            _masses = masses;
            _inverseMasses = inverseMasses;
            _count = count;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var owner = _owner!;
            var level = owner._levels[0];
            var (begin, end) = Chunk.Range(chunk, chunkCount, level.Count);
            var (first, last) = level.BlockRange(begin, end);
            Array.Clear(level.Values, 9 * first, 9 * (last - first)); // the diagonal blocks of the rows
            var (offFirst, offLast) = level.OffDiagonalRange(begin, end);
            Array.Clear(level.Values, 9 * offFirst, 9 * (offLast - offFirst));
            fixed (double* values = level.Values)
            fixed (int* memberStart = owner._memberStart, members = owner._members)
            {
                for (var a = begin; a < end; a++)
                {
                    var d = values + (9L * a);
                    for (var k = memberStart[a]; k < memberStart[a + 1]; k++)
                    {
                        var i = members[k];
                        if (_inverseMasses[i] == 0.0)
                        {
                            continue;
                        }

                        var f = _fine + (9L * i);
                        var mi = _masses[i];
                        d[0] += f[0] - mi;
                        d[1] += f[1];
                        d[2] += f[2];
                        d[3] += f[3];
                        d[4] += f[4] - mi;
                        d[5] += f[5];
                        d[6] += f[6];
                        d[7] += f[7];
                        d[8] += f[8] - mi;
                    }
                }
            }

            _system!.AddCouplingBlocks(
                level.Values, owner._targets[2 * chunk].AsSpan(0, _count), owner._targets[(2 * chunk) + 1].AsSpan(0, _count));
            var v = level.Values;
            for (var k = 9 * first; k < 9 * last; k++)
            {
                v[k] = -v[k];
            }

            for (var k = 9 * offFirst; k < 9 * offLast; k++)
            {
                v[k] = -v[k];
            }
        }
    }

    /// <summary>
    /// For each of the <see cref="Chunks"/> chunks of aggregates that the fine passes run in, the particles its
    /// aggregates' members cover, [first, end), when they are exactly that range of indices (each particle in one
    /// aggregate, so the chunks' ranges are disjoint), else (-1, -1): two values per chunk. A cloth's aggregates are
    /// numbered along its rows, so on a cloth every chunk's members are a range of rows.
    /// </summary>
    private static int[] ContiguousChunkMembers(int[] memberStart, int[] members, int aggregates)
    {
        var ranges = new int[2 * Chunks];
        for (var c = 0; c < Chunks; c++)
        {
            var (begin, end) = Chunk.Range(c, Chunks, aggregates);
            int first = int.MaxValue, last = -1;
            for (var m = memberStart[begin]; m < memberStart[end]; m++)
            {
                first = Math.Min(first, members[m]);
                last = Math.Max(last, members[m]);
            }

            var contiguous = last >= 0 && last - first + 1 == memberStart[end] - memberStart[begin];
            ranges[2 * c] = contiguous ? first : -1;
            ranges[(2 * c) + 1] = contiguous ? last + 1 : -1;
        }

        return ranges;
    }

    /// <summary>The aggregation hierarchy for the current couplings: allocates, and runs only when the topology changes.</summary>
    private void Build(ILinearizableSystem system, int count, int particles)
    {
        _first = new int[count];
        _second = new int[count];
        _checkFirst = new int[count]; // (here, so that the next step's check allocates nothing)
        _checkSecond = new int[count];
        system.WriteCouplings(_first, _second);
        _levels = Array.Empty<Level>();
        _filteredFor = Array.Empty<bool>();

        // Marked as built only once the couplings are checked: a hierarchy that failed here is built (and fails) again
        // at the next step, instead of that step finding the same couplings and falling back to block Jacobi silently.
        _couplings = -1;
        _particles = -1;
        for (var e = 0; e < count; e++)
        {
            if ((uint)_first[e] >= (uint)particles || (uint)_second[e] >= (uint)particles)
            {
                throw new InvalidOperationException(
                    $"Coupling {e} joins particles {_first[e]} and {_second[e]}; the system has {particles}.");
            }
        }

        _couplings = count;
        _particles = particles;

        var fine = CouplingGraph.FromPairs(particles, _first, _second, count);
        if (particles <= CoarsestNodes || fine.EdgeCount == 0)
        {
            return;
        }

        var levels = new List<Level>();
        var map = CouplingGraph.PairTwice(fine, out var coarseCount);
        var graph = fine.Contract(map, coarseCount);
        if (coarseCount > 0.9 * particles)
        {
            return; // hardly coupled: block Jacobi does as well
        }

        _aggregate = map;
        (_memberStart, _members) = CouplingGraph.Members(map, coarseCount);
        _chunkMembers = ContiguousChunkMembers(_memberStart, _members, coarseCount);
        var level = new Level(graph);
        _forwardTarget = new int[count];
        _backwardTarget = new int[count];
        for (var e = 0; e < count; e++)
        {
            int i = _first[e], j = _second[e];
            if (i == j)
            {
                _forwardTarget[e] = _backwardTarget[e] = -1;
                continue;
            }

            _forwardTarget[e] = level.Target(map[i], map[j]);
            _backwardTarget[e] = level.Target(map[j], map[i]);
        }

        levels.Add(level);
        while (level.Count > CoarsestNodes && levels.Count < MaxLevels)
        {
            var nextMap = CouplingGraph.PairTwice(graph, out var nextCount);
            if (nextCount > 0.9 * level.Count)
            {
                break;
            }

            graph = graph.Contract(nextMap, nextCount);
            var next = new Level(graph);
            level.LinkTo(next, nextMap);
            levels.Add(next);
            level = next;
        }

        _levels = levels.ToArray();
    }

    /// <summary>
    /// <see cref="Restrict"/> in fixed chunks of level-1 aggregates: B_I = sum of r_i over the free members of aggregate
    /// I, in increasing member order, then X_I = D_I^-1 B_I when level 1 is smoothed (it is not the coarsest).
    /// </summary>
    private sealed class RestrictionPass : IParallelWork
    {
        private double* _r;
        private double* _inverseMasses;
        private int* _memberStart;
        private int* _members;
        private int _aggregates;
        private double* _coarseB;
        private double* _coarseInverse;
        private double* _coarseX;
        private bool _smoothed;

        public void Set(
            double* r, double* inverseMasses, int* memberStart, int* members, int aggregates, double* coarseB,
            double* coarseInverse, double* coarseX, bool smoothed)
        {
            _r = r;
            _inverseMasses = inverseMasses;
            _memberStart = memberStart;
            _members = members;
            _aggregates = aggregates;
            _coarseB = coarseB;
            _coarseInverse = coarseInverse;
            _coarseX = coarseX;
            _smoothed = smoothed;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _aggregates);
            double* residual = _r, inverseMasses = _inverseMasses, coarseB = _coarseB, coarseX = _coarseX, coarseInverse = _coarseInverse;
            int* memberStart = _memberStart, members = _members;
            var smoothed = _smoothed;
            for (var a = begin; a < end; a++)
            {
                double bx = 0.0, by = 0.0, bz = 0.0;
                for (var m = memberStart[a]; m < memberStart[a + 1]; m++)
                {
                    var i = members[m];
                    if (inverseMasses[i] == 0.0)
                    {
                        continue;
                    }

                    var ri = residual + (3L * i);
                    bx += ri[0];
                    by += ri[1];
                    bz += ri[2];
                }

                var b = coarseB + (3L * a);
                b[0] = bx;
                b[1] = by;
                b[2] = bz;
                if (smoothed)
                {
                    Blocks3.Multiply(coarseInverse + (9L * a), b, coarseX + (3L * a));
                }
            }
        }
    }

    /// <summary>
    /// <see cref="UpdateAndRestrict"/> in the chunks of <see cref="RestrictionPass"/>: each chunk updates its aggregates'
    /// members, then restricts their new r and sums their r . r.
    /// </summary>
    private sealed class UpdateAndRestrictionPass : IParallelWork
    {
        private readonly double[] _partial = new double[Chunks];
        private double* _z;
        private double* _jw;
        private double* _masses;
        private double* _coordinateMasses;
        private double _alpha;
        private double _beta;
        private double* _p;
        private double* _s;
        private double* _dv;
        private double* _r;
        private double* _inverseMasses;
        private int* _memberStart;
        private int* _members;
        private int* _chunkMembers;
        private int _aggregates;
        private double* _coarseB;
        private double* _coarseInverse;
        private double* _coarseX;
        private bool _smoothed;

        /// <summary>The update's vectors and scalars (masses once per particle and once per coordinate).</summary>
        public void Set(
            double* z, double* jw, double* masses, double* coordinateMasses, double alpha, double beta, double* p, double* s,
            double* dv, double* r, double* inverseMasses)
        {
            _z = z;
            _jw = jw;
            _masses = masses;
            _coordinateMasses = coordinateMasses;
            _alpha = alpha;
            _beta = beta;
            _p = p;
            _s = s;
            _dv = dv;
            _r = r;
            _inverseMasses = inverseMasses;
        }

        /// <summary>
        /// The aggregates (members, and per chunk [first, end) of its members when they are one range of particles,
        /// else -1, -1) and level 1's B, inverted blocks and X.
        /// </summary>
        public void SetAggregates(
            int* memberStart, int* members, int* chunkMembers, int aggregates, double* coarseB, double* coarseInverse,
            double* coarseX, bool smoothed)
        {
            _memberStart = memberStart;
            _members = members;
            _chunkMembers = chunkMembers;
            _aggregates = aggregates;
            _coarseB = coarseB;
            _coarseInverse = coarseInverse;
            _coarseX = coarseX;
            _smoothed = smoothed;
        }

        public double Sum() => Chunk.Sum(_partial);

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _aggregates);
            if (_chunkMembers[2 * chunk] >= 0)
            {
                // The chunk's members are one range of particles: the update over its coordinates first, with SIMD
                // where the runtime has it (the same operations per component), then the restriction below reads the
                // new r and sums r . r in the same member order as the update per member does.
                ConjugateGradientUpdate.Range(
                    _z, _jw, _coordinateMasses, _p, _s, _dv, _r, _alpha, _beta, 3L * _chunkMembers[2 * chunk], 3L * _chunkMembers[(2 * chunk) + 1]);
                _partial[chunk] = RestrictUpdated(begin, end);
                return;
            }

            _partial[chunk] = UpdateAndRestrictRows(begin, end);
        }

        /// <summary>
        /// Each member of aggregates [begin, end) updated in increasing member order, its r added to B_I when it is free,
        /// then X_I = D_I^-1 B_I; returns the chunk's r . r.
        /// </summary>
        private double UpdateAndRestrictRows(int begin, int end)
        {
            double* residual = _r, z = _z, jw = _jw, p = _p, s = _s, dv = _dv, masses = _masses, inverseMasses = _inverseMasses;
            double* coarseB = _coarseB, coarseX = _coarseX, coarseInverse = _coarseInverse;
            int* memberStart = _memberStart, members = _members;
            double alpha = _alpha, beta = _beta;
            var smoothed = _smoothed;
            var sum = 0.0;
            for (var a = begin; a < end; a++)
            {
                double bx = 0.0, by = 0.0, bz = 0.0;
                for (var m = memberStart[a]; m < memberStart[a + 1]; m++)
                {
                    var i = members[m];
                    var ri = residual + (3L * i);
                    var o = 3L * i;
                    var mass = masses[i];
                    var r0 = ConjugateGradientUpdate.Component(z, jw, mass, p, s, dv, residual, alpha, beta, o);
                    var r1 = ConjugateGradientUpdate.Component(z, jw, mass, p, s, dv, residual, alpha, beta, o + 1);
                    var r2 = ConjugateGradientUpdate.Component(z, jw, mass, p, s, dv, residual, alpha, beta, o + 2);
                    sum += r0 * r0;
                    sum += r1 * r1;
                    sum += r2 * r2;
                    if (inverseMasses[i] == 0.0)
                    {
                        continue;
                    }

                    bx += ri[0];
                    by += ri[1];
                    bz += ri[2];
                }

                var b = coarseB + (3L * a);
                b[0] = bx;
                b[1] = by;
                b[2] = bz;
                if (smoothed)
                {
                    Blocks3.Multiply(coarseInverse + (9L * a), b, coarseX + (3L * a));
                }
            }

            return sum;
        }

        /// <summary>
        /// The restriction of aggregates [begin, end) after their members' update: B_I and X_I as above, and r . r over
        /// the members in the same order as the update per member sums it. Returns the chunk's r . r.
        /// </summary>
        private double RestrictUpdated(int begin, int end)
        {
            double* residual = _r, inverseMasses = _inverseMasses, coarseB = _coarseB, coarseX = _coarseX, coarseInverse = _coarseInverse;
            int* memberStart = _memberStart, members = _members;
            var smoothed = _smoothed;
            var sum = 0.0;
            for (var a = begin; a < end; a++)
            {
                double bx = 0.0, by = 0.0, bz = 0.0;
                for (var m = memberStart[a]; m < memberStart[a + 1]; m++)
                {
                    var i = members[m];
                    var ri = residual + (3L * i);
                    double r0 = ri[0], r1 = ri[1], r2 = ri[2];
                    sum += r0 * r0;
                    sum += r1 * r1;
                    sum += r2 * r2;
                    if (inverseMasses[i] == 0.0)
                    {
                        continue;
                    }

                    bx += r0;
                    by += r1;
                    bz += r2;
                }

                var b = coarseB + (3L * a);
                b[0] = bx;
                b[1] = by;
                b[2] = bz;
                if (smoothed)
                {
                    Blocks3.Multiply(coarseInverse + (9L * a), b, coarseX + (3L * a));
                }
            }

            return sum;
        }
    }

    /// <summary>
    /// The end of <see cref="CycleAndProlong"/> in the chunks of <see cref="RestrictionPass"/>: level 1's post-smoothing
    /// of the chunk's aggregates (when level 1 is not the coarsest), then z_i = D_i^-1 r_i + X_1[a] on their free members
    /// and 0 on pinned ones, and the chunk's r . z.
    /// </summary>
    private sealed class PostSmoothAndProlongPass : IParallelWork
    {
        private readonly double[] _partial = new double[Chunks];
        private double* _r;
        private double* _inverses;
        private double* _inverseMasses;
        private int* _memberStart;
        private int* _members;
        private int _aggregates;
        private Level? _level;
        private double* _coarseX;
        private double* _z;

        /// <summary>
        /// <paramref name="level"/>: level 1 when its post-smoothing is fused here (it writes the new X_1 into
        /// <paramref name="coarseX"/>, its smoothed buffer), null when X_1 is final (the coarsest solve's, in
        /// <paramref name="coarseX"/>).
        /// </summary>
        public void Set(
            double* r, double* inverses, double* inverseMasses, int* memberStart, int* members, int aggregates, Level? level,
            double* coarseX, double* z)
        {
            _r = r;
            _inverses = inverses;
            _inverseMasses = inverseMasses;
            _memberStart = memberStart;
            _members = members;
            _aggregates = aggregates;
            _level = level;
            _coarseX = coarseX;
            _z = z;
        }

        public double Sum() => Chunk.Sum(_partial);

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _aggregates);
            _level?.PostSmoothRows(begin, end, _coarseX);
            _partial[chunk] = ProlongRows(begin, end);
        }

        /// <summary>
        /// z_i = D_i^-1 r_i + X[a] on the free members of aggregates [begin, end), 0 on pinned ones; returns their r . z.
        /// The addresses in locals: read from the fields, they were loaded again after every store to z.
        /// </summary>
        private double ProlongRows(int begin, int end)
        {
            double* residual = _r, preconditioned = _z, inverses = _inverses, inverseMasses = _inverseMasses, coarse = _coarseX;
            int* memberStart = _memberStart, members = _members;
            var sum = 0.0;
            for (var a = begin; a < end; a++)
            {
                var x = coarse + (3L * a);
                for (var k = memberStart[a]; k < memberStart[a + 1]; k++)
                {
                    var i = members[k];
                    double* ri = residual + (3L * i), zi = preconditioned + (3L * i), m = inverses + (6L * i);
                    if (inverseMasses[i] == 0.0)
                    {
                        zi[0] = zi[1] = zi[2] = 0.0;
                        continue;
                    }

                    double rx = ri[0], ry = ri[1], rzz = ri[2];
                    var zx = (m[0] * rx) + (m[1] * ry) + (m[2] * rzz) + x[0]; // D_i^-1 as its upper triangle
                    var zy = (m[1] * rx) + (m[3] * ry) + (m[4] * rzz) + x[1];
                    var zz = (m[2] * rx) + (m[4] * ry) + (m[5] * rzz) + x[2];
                    zi[0] = zx;
                    zi[1] = zy;
                    zi[2] = zz;
                    sum += (rx * zx) + (ry * zy) + (rzz * zz);
                }
            }

            return sum;
        }
    }

    /// <summary>
    /// One coarse level: diagonal and off-diagonal 3 x 3 blocks (compressed rows with both directions of every pair in
    /// its sparsity, columns increasing; each pair's block stored once), the inverted diagonal, the right-hand side B
    /// and solution X of its cycle, and its link to the next.
    /// </summary>
    /// <remarks>
    /// The operator is symmetric, A_ji = A_ij^T, so each pair's block is stored once, in the row of the smaller
    /// aggregate (the upper triangle, in row order: a row's upper blocks lie together), and a row reads the blocks
    /// left of its diagonal transposed from the rows above it. A sweep streams half the bytes it would with both
    /// directions stored (level 1 of the 64 x 64 cloth: 295 KB of off-diagonal blocks instead of 590 KB, read twice
    /// per iteration), and the rows it re-reads were read a few rows earlier, so they are still in the cache.
    /// </remarks>
    private sealed class Level : IParallelWork
    {
        private const int ResidualRestrictPass = 0;
        private const int PostSmoothPass = 1;
        private const int InvertPass = 2;
        private const int GalerkinPass = 3;

        // Below this many rows a level's passes stay on the calling thread: waking the workers would cost more. 256: at
        // the runner's 200 us spin limit the workers are awake between the cycle's passes, and on the 64 x 64 cloth
        // (levels of 1024, 256, 64 and 16 aggregates) running level 2 on two threads made the two-thread second 151 ms
        // against 169 ms with 1024 (means of the fastest rounds of four alternating runs of `runner --engine
        // implicit-euler --n 64`). The 64-row level's passes (a few microseconds) stay on the calling thread.
        private const int ParallelRows = 256;

        /// <summary>
        /// Whether the sweeps take a row's three components as lanes of one System.Numerics.Vector (CoreCLR with
        /// 256-bit vectors: four lanes of double), else one at a time (Mono, IL2CPP, other widths). Per lane the
        /// same multiplications, additions and subtractions in the same order, so the same bits.
        /// </summary>
        private static bool Lanes => Vector.IsHardwareAccelerated && Vector<double>.Count == 4;

        private readonly int[] _rowStart;
        private readonly int[] _column;
        private readonly int[] _split;     // per row: its first entry right of the diagonal (columns are increasing)
        private readonly int[] _slot;      // per entry: its stored block, counted after the diagonal ones
        private readonly int[] _upperStart; // per row, and one past the last: its first stored off-diagonal block
        private double[] _smoothed; // where a post-smoothing writes the new X (the rows still to come read the old one)

        // The lanes path (Lanes): each row's blocks in row order, the diagonal first, each 3 x 3 block by columns, so
        // that a block times a vector is three column vectors scaled and added, four lanes at a time (the fourth
        // unused); and the inverted diagonal blocks by columns. Rewritten from Values and Inverse at every Invert.
        private readonly double[] _laneBlocks = Array.Empty<double>();
        private readonly double[] _laneInverse = Array.Empty<double>();
        private int[] _nextAggregate = Array.Empty<int>();
        private int[] _nextMemberStart = Array.Empty<int>();
        private int[] _nextMembers = Array.Empty<int>();
        private Level? _next;
        private Level? _above; // the level a post-smoothing prolongs into
        private bool _smoothNext;
        private int _operation;
        private int _passCount;
        private int[] _nextTarget = Array.Empty<int>();
        private double[]? _dense;
        private bool _denseValid;

        public Level(CouplingGraph graph)
        {
            Count = graph.Count;
            _rowStart = graph.RowStart;
            _column = graph.Column;
            (_split, _slot, _upperStart) = UpperSlots(Count, _rowStart, _column);
            Values = new double[9 * (Count + _upperStart[Count])];
            Inverse = new double[9 * Count];

            // One value past the rows: the lanes path reads a row's B and X as four values (the fourth unused).
            B = new double[(3 * Count) + 1];
            X = new double[(3 * Count) + 1];
            _smoothed = new double[(3 * Count) + 1];
            if (Lanes)
            {
                _laneBlocks = new double[(9 * (Count + _column.Length)) + 1];
                _laneInverse = new double[(9 * Count) + 1];
            }
        }

        public int Count { get; }

        /// <summary>
        /// The blocks: the diagonal ones (block i for row i), then each pair's off-diagonal block A_ij with i &lt; j once
        /// (block Count + slot of entry k; the entry (j, i) reads it transposed).
        /// </summary>
        public double[] Values { get; }

        public double[] Inverse { get; }

        public double[] B { get; }

        public double[] X { get; private set; }

        /// <summary>The buffer a post-smoothing writes into; <see cref="SwapSmoothed"/> makes it <see cref="X"/>.</summary>
        public double[] Smoothed => _smoothed;

        /// <summary>True when block <paramref name="target"/> of <see cref="Values"/> lies in rows [begin, end).</summary>
        public bool InRows(int target, int begin, int end) =>
            target < Count ? target >= begin && target < end : target - Count >= _upperStart[begin] && target - Count < _upperStart[end];

        /// <summary>The diagonal blocks of rows [begin, end) in <see cref="Values"/>.</summary>
        public (int First, int Last) BlockRange(int begin, int end) => (begin, end);

        /// <summary>The off-diagonal blocks stored in rows [begin, end) of <see cref="Values"/>.</summary>
        public (int First, int Last) OffDiagonalRange(int begin, int end) => (Count + _upperStart[begin], Count + _upperStart[end]);

        /// <summary>
        /// The index in <see cref="Values"/> of block (row, column) when it is stored as it is: the diagonal, or
        /// row &lt; column; -1 for row &gt; column, whose block is the transpose of (column, row).
        /// </summary>
        public int Target(int row, int column)
        {
            if (row == column)
            {
                return row;
            }

            if (row > column)
            {
                return -1;
            }

            return Count + _slot[Entry(_rowStart, _column, row, column)];
        }

        /// <summary>The entry of (row, column) in compressed rows with increasing columns.</summary>
        private static int Entry(int[] rowStart, int[] column, int row, int col)
        {
            var k = Array.BinarySearch(column, rowStart[row], rowStart[row + 1] - rowStart[row], col);
            if (k < 0)
            {
                throw new InvalidOperationException($"No coarse block ({row}, {col}): the aggregation is inconsistent.");
            }

            return k;
        }

        /// <summary>
        /// Numbers the entries right of the diagonal in row order (the stored blocks) and gives each entry left of it
        /// the number of its mirror (j, i); the graph is symmetric (every pair in both rows).
        /// </summary>
        private static (int[] Split, int[] Slot, int[] UpperStart) UpperSlots(int count, int[] rowStart, int[] column)
        {
            var split = new int[count];
            var slot = new int[column.Length];
            var upperStart = new int[count + 1];
            var next = 0;
            for (var i = 0; i < count; i++)
            {
                upperStart[i] = next;
                var k = rowStart[i];
                while (k < rowStart[i + 1] && column[k] < i)
                {
                    k++;
                }

                split[i] = k;
                for (; k < rowStart[i + 1]; k++)
                {
                    slot[k] = next++;
                }
            }

            upperStart[count] = next;
            for (var i = 0; i < count; i++)
            {
                for (var k = rowStart[i]; k < split[i]; k++)
                {
                    slot[k] = slot[Entry(rowStart, column, column[k], i)];
                }
            }

            return (split, slot, upperStart);
        }

        public void LinkTo(Level next, int[] map)
        {
            _nextAggregate = map;
            (_nextMemberStart, _nextMembers) = CouplingGraph.Members(map, next.Count);
            _nextTarget = new int[_column.Length];
            for (var i = 0; i < Count; i++)
            {
                for (var k = _rowStart[i]; k < _rowStart[i + 1]; k++)
                {
                    _nextTarget[k] = next.Target(map[i], map[_column[k]]);
                }
            }
        }

        /// <summary>
        /// Inverts the diagonal blocks, in one pass over the rows (on the runner for large levels); a zero block (an
        /// aggregate of pinned particles only) becomes the identity.
        /// </summary>
        public void Invert(IParallelRunner? runner) => RunPass(InvertPass, Count, runner);

        /// <summary>Rows [begin, end) of <see cref="Invert"/>, then their blocks by columns for the lanes path.</summary>
        private void InvertRows(int begin, int end)
        {
            var d = Values;
            for (var i = begin; i < end; i++)
            {
                var o = 9 * i;
                if (d[o] == 0.0 && d[o + 4] == 0.0 && d[o + 8] == 0.0)
                {
                    d[o] = d[o + 4] = d[o + 8] = 1.0;
                }

                if (!Blocks3.Invert(d, o, Inverse, o))
                {
                    Array.Clear(Inverse, o, 9);
                    Inverse[o] = 1.0 / Math.Max(d[o], double.Epsilon);
                    Inverse[o + 4] = 1.0 / Math.Max(d[o + 4], double.Epsilon);
                    Inverse[o + 8] = 1.0 / Math.Max(d[o + 8], double.Epsilon);
                }
            }

            if (Lanes)
            {
                fixed (double* values = Values, inverse = Inverse, lanes = _laneBlocks, inverseLanes = _laneInverse)
                {
                    for (var i = begin; i < end; i++)
                    {
                        LaneRow(i, values, inverse, lanes, inverseLanes);
                    }
                }
            }
        }

        /// <summary>
        /// Row i's blocks and inverted diagonal block by columns for the lanes path: the diagonal block and each entry's
        /// block A_ij, a block right of the diagonal transposed from its row-major storage, one left of it copied as it
        /// is (its storage is A_ji = A_ij^T row by row, which is A_ij column by column).
        /// </summary>
        private void LaneRow(int i, double* values, double* inverse, double* lanes, double* inverseLanes)
        {
            var k = _rowStart[i];
            Transpose(values + (9L * i), lanes + (9L * (i + k)));
            Transpose(inverse + (9L * i), inverseLanes + (9L * i));
            for (; k < _rowStart[i + 1]; k++)
            {
                double* stored = values + (9L * (Count + _slot[k])), to = lanes + (9L * (i + 1 + k));
                if (k < _split[i])
                {
                    for (var q = 0; q < 9; q++)
                    {
                        to[q] = stored[q];
                    }
                }
                else
                {
                    Transpose(stored, to);
                }
            }
        }

        /// <summary>A row-major 3 x 3 block written by columns: to[3 c + r] = from[3 r + c].</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        private static void Transpose(double* from, double* to)
        {
            (to[0], to[1], to[2]) = (from[0], from[3], from[6]);
            (to[3], to[4], to[5]) = (from[1], from[4], from[7]);
            (to[6], to[7], to[8]) = (from[2], from[5], from[8]);
        }

        /// <summary>
        /// The next level's operator: every block of this one added where its row and column aggregates meet, in one pass
        /// over the next level's aggregates (on the runner for large levels). Row i's blocks all land in the row of its
        /// aggregate (its diagonal block, or a block right of it: a block whose aggregates are in decreasing order is
        /// left to its mirror, which the next level stores), so each aggregate assembles its own row from its members'
        /// rows, in increasing member order: every block gets its terms in increasing row order, as a loop over all the
        /// rows gives them, whatever the chunks.
        /// </summary>
        public void GalerkinInto(Level next, IParallelRunner? runner)
        {
            _next = next;
            RunPass(GalerkinPass, next.Count, runner);
        }

        /// <summary>Aggregates [begin, end) of the next level's operator (see <see cref="GalerkinInto"/>): their rows cleared, then summed.</summary>
        private void GalerkinRows(int begin, int end, double* values, double* nextValues, int* rowStart, int* split, int* slot, int* start, int* members)
        {
            var next = _next!;
            var (first, last) = next.BlockRange(begin, end);
            new Span<double>(nextValues + (9L * first), 9 * (last - first)).Clear();
            var (offFirst, offLast) = next.OffDiagonalRange(begin, end);
            new Span<double>(nextValues + (9L * offFirst), 9 * (offLast - offFirst)).Clear();
            fixed (int* target = _nextTarget)
            {
                for (var a = begin; a < end; a++)
                {
                    for (var m = start[a]; m < start[a + 1]; m++)
                    {
                        // Row i's blocks A_ij in column order, those left of the diagonal read transposed.
                        var i = members[m];
                        Blocks3.Add(nextValues + (9L * a), values + (9L * i));
                        for (var k = rowStart[i]; k < split[i]; k++)
                        {
                            if (target[k] >= 0)
                            {
                                Blocks3.AddTransposed(nextValues + (9L * target[k]), values + (9L * (Count + slot[k])));
                            }
                        }

                        for (var k = split[i]; k < rowStart[i + 1]; k++)
                        {
                            if (target[k] >= 0)
                            {
                                Blocks3.Add(nextValues + (9L * target[k]), values + (9L * (Count + slot[k])));
                            }
                        }
                    }
                }
            }
        }

        /// <summary>
        /// The next level's B = P^T (B - A X), with this level's X = D^-1 B already done, and when
        /// <paramref name="smoothNext"/> the next level's own pre-smoothing from zero, X_next = D_next^-1 B_next: one
        /// pass over the next level's aggregates, each summing its members' residual rows in increasing member order.
        /// </summary>
        public void RestrictResidual(Level next, bool smoothNext, IParallelRunner? runner)
        {
            _next = next;
            _smoothNext = smoothNext;
            RunPass(ResidualRestrictPass, next.Count, runner);
        }

        /// <summary>X += P X_next: each row adds its aggregate's correction from the level below, on the calling thread.</summary>
        public void Prolong(Level next)
        {
            fixed (double* x = X, nextX = next.X)
            fixed (int* aggregate = _nextAggregate)
            {
                for (var i = 0; i < Count; i++)
                {
                    double* xi = x + (3L * i), ci = nextX + (3L * aggregate[i]);
                    xi[0] += ci[0];
                    xi[1] += ci[1];
                    xi[2] += ci[2];
                }
            }
        }

        /// <summary>
        /// The post-smoothing sweep X + D^-1 (B - A X) after the prolongation, in one pass, with the prolongation into
        /// the level above: each row's new X added to its members there (X_above += P X, the additions of
        /// <see cref="Prolong"/>).
        /// </summary>
        public void PostSmooth(Level next, Level above, IParallelRunner? runner)
        {
            _next = next;
            _above = above;
            RunPass(PostSmoothPass, Count, runner);
            _above = null;
            SwapSmoothed();
        }

        /// <summary>Makes the buffer the post-smoothing wrote into this level's X.</summary>
        public void SwapSmoothed() => (X, _smoothed) = (_smoothed, X);

        /// <summary>
        /// Rows [begin, end) of the post-smoothing sweep (see <see cref="PostSmooth"/>) into <paramref name="outputs"/>
        /// (3 values per row), the level's arrays pinned once for the rows instead of once a row (94 instructions a row).
        /// </summary>
        public void PostSmoothRows(int begin, int end, double* outputs)
        {
            fixed (double* b = B, x = X, inverse = Inverse, values = Values, lanes = _laneBlocks, inverseLanes = _laneInverse)
            fixed (int* rowStart = _rowStart, column = _column, split = _split, slot = _slot)
            {
                for (var i = begin; i < end; i++)
                {
                    PostSmoothRowCore(i, values, rowStart, column, split, slot, b, x, inverse, lanes, inverseLanes, outputs + (3L * i));
                }
            }
        }

        /// <summary>
        /// output = X_i + D_i^-1 (B_i - sum_j A_ij X_j) (X read only: the rows still to come need the old one), from
        /// the lanes copies (<paramref name="lanes"/>, <paramref name="inverseLanes"/>) where <see cref="Lanes"/>.
        /// </summary>
        private void PostSmoothRowCore(
            int i, double* values, int* rowStart, int* column, int* split, int* slot, double* b, double* x, double* inverse,
            double* lanes, double* inverseLanes, double* output)
        {
            if (Lanes)
            {
                // x_i + W r as W's columns scaled by r's components: per lane ((W_l0 r_0 + W_l1 r_1) + W_l2 r_2), as below.
                var rl = ResidualLanes(i, lanes, rowStart, column, b, x);
                var wi = inverseLanes + (9L * i);
                var t = (Load(wi) * new Vector<double>(rl[0])) + (Load(wi + 3) * new Vector<double>(rl[1]));
                var o = Load(x + (3L * i)) + (t + (Load(wi + 6) * new Vector<double>(rl[2])));
                output[0] = o[0];
                output[1] = o[1];
                output[2] = o[2];
                return;
            }

            var r = ResidualRow(i, values, rowStart, column, split, slot, b, x);
            double* w = inverse + (9L * i), xi = x + (3L * i);
            output[0] = xi[0] + ((w[0] * r.X) + (w[1] * r.Y) + (w[2] * r.Z));
            output[1] = xi[1] + ((w[3] * r.X) + (w[4] * r.Y) + (w[5] * r.Z));
            output[2] = xi[2] + ((w[6] * r.X) + (w[7] * r.Y) + (w[8] * r.Z));
        }

        /// <summary>Row i of the residual, B_i - A_ii X_i - sum_j A_ij X_j, in that order.</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        private Vector3d ResidualRow(int i, double* values, int* rowStart, int* column, int* split, int* slot, double* b, double* x)
        {
            double* d = values + (9L * i), xi = x + (3L * i);
            double x0 = xi[0], x1 = xi[1], x2 = xi[2];
            var bi = b + (3L * i);
            var r0 = bi[0] - ((d[0] * x0) + (d[1] * x1) + (d[2] * x2));
            var r1 = bi[1] - ((d[3] * x0) + (d[4] * x1) + (d[5] * x2));
            var r2 = bi[2] - ((d[6] * x0) + (d[7] * x1) + (d[8] * x2));
            int k = rowStart[i], middle = split[i], end = rowStart[i + 1];
            for (; k < middle; k++)
            {
                // Left of the diagonal: A_ij = A_ji^T, stored in row j.
                double* m = values + (9L * (Count + slot[k])), xj = x + (3L * column[k]);
                double y0 = xj[0], y1 = xj[1], y2 = xj[2];
                r0 -= (m[0] * y0) + (m[3] * y1) + (m[6] * y2);
                r1 -= (m[1] * y0) + (m[4] * y1) + (m[7] * y2);
                r2 -= (m[2] * y0) + (m[5] * y1) + (m[8] * y2);
            }

            for (; k < end; k++)
            {
                double* m = values + (9L * (Count + slot[k])), xj = x + (3L * column[k]);
                double y0 = xj[0], y1 = xj[1], y2 = xj[2];
                r0 -= (m[0] * y0) + (m[1] * y1) + (m[2] * y2);
                r1 -= (m[3] * y0) + (m[4] * y1) + (m[5] * y2);
                r2 -= (m[6] * y0) + (m[7] * y1) + (m[8] * y2);
            }

            return new Vector3d(r0, r1, r2);
        }

        /// <summary>
        /// <see cref="ResidualRow"/> with the row's three components as lanes (the fourth unused): each block times x_j
        /// as its columns scaled by x_j's components, ((A_l0 y_0 + A_l1 y_1) + A_l2 y_2) per lane, subtracted in the
        /// same order: the same bits.
        /// </summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        private static Vector<double> ResidualLanes(int i, double* blocks, int* rowStart, int* column, double* b, double* x)
        {
            int k = rowStart[i], end = rowStart[i + 1];
            double* d = blocks + (9L * (i + k)), xi = x + (3L * i);
            var r = Load(b + (3L * i)) - ColumnsTimes(d, xi);
            for (; k < end; k++)
            {
                r -= ColumnsTimes(blocks + (9L * (i + 1 + k)), x + (3L * column[k]));
            }

            return r;
        }

        /// <summary>A block stored by columns times the 3-vector y, as lanes: (c_0 y_0 + c_1 y_1) + c_2 y_2.</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        private static Vector<double> ColumnsTimes(double* columns, double* y) =>
            ((Load(columns) * new Vector<double>(y[0])) + (Load(columns + 3) * new Vector<double>(y[1])))
            + (Load(columns + 6) * new Vector<double>(y[2]));

        /// <summary>Four values from <paramref name="at"/> (each array the lanes path reads has one value past its last row).</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        private static Vector<double> Load(double* at) => *(Vector<double>*)at;

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _passCount);
            if (_operation == InvertPass)
            {
                InvertRows(begin, end);
                return;
            }

            fixed (double* b = B, x = X, smoothed = _smoothed, inverse = Inverse, values = Values, lanes = _laneBlocks, inverseLanes = _laneInverse)
            fixed (int* rowStart = _rowStart, column = _column, split = _split, slot = _slot)
            fixed (double* nextB = _next!.B, nextX = _next.X, nextInverse = _next.Inverse)
            fixed (int* aggregate = _nextAggregate, start = _nextMemberStart, members = _nextMembers)
            {
                if (_operation == GalerkinPass)
                {
                    fixed (double* nextValues = _next.Values)
                    {
                        GalerkinRows(begin, end, values, nextValues, rowStart, split, slot, start, members);
                    }

                    return;
                }

                if (_operation == PostSmoothPass)
                {
                    var above = _above!;
                    fixed (double* aboveX = above.X)
                    fixed (int* aboveStart = above._nextMemberStart, aboveMembers = above._nextMembers)
                    {
                        for (var i = begin; i < end; i++)
                        {
                            var c = smoothed + (3L * i);
                            PostSmoothRowCore(i, values, rowStart, column, split, slot, b, x, inverse, lanes, inverseLanes, c);
                            for (var m = aboveStart[i]; m < aboveStart[i + 1]; m++)
                            {
                                var xm = aboveX + (3L * aboveMembers[m]);
                                xm[0] += c[0];
                                xm[1] += c[1];
                                xm[2] += c[2];
                            }
                        }
                    }

                    return;
                }

                for (var a = begin; a < end; a++)
                {
                    double b0 = 0.0, b1 = 0.0, b2 = 0.0;
                    if (Lanes)
                    {
                        var sum = Vector<double>.Zero; // the members' residual rows added lane by lane, in member order
                        for (var k = start[a]; k < start[a + 1]; k++)
                        {
                            sum += ResidualLanes(members[k], lanes, rowStart, column, b, x);
                        }

                        (b0, b1, b2) = (sum[0], sum[1], sum[2]);
                    }
                    else
                    {
                        for (var k = start[a]; k < start[a + 1]; k++)
                        {
                            var r = ResidualRow(members[k], values, rowStart, column, split, slot, b, x); // member k's residual row
                            b0 += r.X;
                            b1 += r.Y;
                            b2 += r.Z;
                        }
                    }

                    var nb = nextB + (3L * a);
                    nb[0] = b0;
                    nb[1] = b1;
                    nb[2] = b2;
                    if (_smoothNext)
                    {
                        Blocks3.Multiply(nextInverse + (9L * a), nb, nextX + (3L * a));
                    }
                }
            }
        }

        /// <summary>Runs a pass over <paramref name="count"/> items in <see cref="Chunks"/> chunks: on the runner for large levels.</summary>
        private void RunPass(int operation, int count, IParallelRunner? runner)
        {
            _operation = operation;
            _passCount = count;
            Chunk.RunAll(Count >= ParallelRows ? runner : null, this, Chunks); // small levels stay on the calling thread
        }

        /// <summary>The map of this level's rows into the next level's aggregates (empty on the coarsest).</summary>
        public int[] NextAggregate => _nextAggregate;

        /// <summary>The operator as a dense row-major matrix, 3 Count values a side (for tests: it allocates).</summary>
        public double[] Dense()
        {
            var n = 3 * Count;
            var a = new double[n * n];
            FillDense(a, n);
            return a;
        }

        /// <summary>Writes the operator into <paramref name="a"/>, dense and row-major with <paramref name="n"/> = 3 Count.</summary>
        private void FillDense(double[] a, int n)
        {
            for (var i = 0; i < Count; i++)
            {
                for (var p = 0; p < 3; p++)
                {
                    for (var q = 0; q < 3; q++)
                    {
                        a[(((3 * i) + p) * n) + (3 * i) + q] = Values[(9 * i) + (3 * p) + q];
                    }
                }

                for (var k = _rowStart[i]; k < _rowStart[i + 1]; k++)
                {
                    var j = _column[k];
                    var block = 9 * (Count + _slot[k]);
                    var transposed = k < _split[i]; // left of the diagonal: the transpose of block (j, i)
                    for (var p = 0; p < 3; p++)
                    {
                        for (var q = 0; q < 3; q++)
                        {
                            a[(((3 * i) + p) * n) + (3 * j) + q] = Values[block + (transposed ? (3 * q) + p : (3 * p) + q)];
                        }
                    }
                }
            }
        }

        /// <summary>Factorises the dense operator of a small level (Cholesky); block Jacobi if it is large or not positive definite.</summary>
        public void FactorDense()
        {
            _denseValid = false;
            if (Count > CoarsestNodes)
            {
                return;
            }

            var n = 3 * Count;
            _dense ??= new double[n * n];
            var a = _dense;
            Array.Clear(a, 0, a.Length);
            FillDense(a, n);
            _denseValid = DenseLinearSolver.FactorCholesky(a, n);
        }

        /// <summary>X = A^-1 B by the Cholesky factors, or X = D^-1 B when there are none.</summary>
        public void SolveCoarsest()
        {
            if (!_denseValid)
            {
                fixed (double* b = B, x = X, inverse = Inverse)
                {
                    Blocks3.MultiplyAll(inverse, b, x, Count);
                }

                return;
            }

            DenseLinearSolver.SolveCholesky(_dense!, 3 * Count, B, X);
        }
    }
}
