using System;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Integrators.Multigrid;

/// <summary>
/// The first coarse level's operator A_1 = P^T A P from the fine one, A = M - J: the fine diagonal blocks M - J_ii and
/// the coupling blocks -J_ij summed per aggregate, the couplings of pinned particles left out.
/// </summary>
/// <remarks>
/// For piecewise-constant P, A_1[I, J] is the sum of the blocks A_ij with i in I and j in J, and a coupling inside an
/// aggregate lands on its diagonal. The forces add their J_ij straight into the aggregates' blocks through a map from
/// each coupling to its level-1 block (<see cref="ILinearizableSystem.AddCouplingBlocks"/>, the scatter-add of finite
/// element assembly), so a block holds -A_1 until its sign is turned at the end. On a runner, each part assembles the
/// block rows of a range of aggregates, with the targets outside it masked: every block still gets its terms in the
/// same order. The couplings of pinned particles are masked the same way, so the assembly follows pinning without a
/// rebuild of the hierarchy.
/// </remarks>
internal sealed unsafe class FineGalerkinAssembly
{
    private readonly AssemblyPass _pass = new();
    private int[] _first = Array.Empty<int>();
    private int[] _second = Array.Empty<int>();

    // The block of level 1 that each fine coupling's A_ij (forward) and A_ji (backward) land in (-1: none, or not the
    // direction stored).
    private int[] _forwardTarget = Array.Empty<int>();
    private int[] _backwardTarget = Array.Empty<int>();

    // Those targets masked for each part of the assembly, forward then backward: for one part, for the runner's parts,
    // and the set in use; and the pinned particles they were masked for.
    private int[][] _whole = Array.Empty<int[]>();
    private int[][] _parted = Array.Empty<int[]>();
    private int[][] _targets = Array.Empty<int[]>();
    private bool[] _filteredFor = Array.Empty<bool>();

    /// <summary>
    /// Maps the couplings (<paramref name="first"/>, <paramref name="second"/>) to their blocks of
    /// <paramref name="level"/> through the particles' aggregates: at each build of the hierarchy.
    /// </summary>
    public void Link(int[] first, int[] second, int count, int[] aggregate, CoarseLevel level)
    {
        _first = first;
        _second = second;
        _filteredFor = Array.Empty<bool>();
        _forwardTarget = new int[count];
        _backwardTarget = new int[count];
        for (var e = 0; e < count; e++)
        {
            int i = first[e], j = second[e];
            if (i == j)
            {
                _forwardTarget[e] = _backwardTarget[e] = -1;
                continue;
            }

            _forwardTarget[e] = level.Target(aggregate[i], aggregate[j]);
            _backwardTarget[e] = level.Target(aggregate[j], aggregate[i]);
        }
    }

    /// <summary>
    /// Writes A_1 into <paramref name="level"/>'s blocks from the system's current linearisation
    /// (<paramref name="fineDiagonal"/>: J_ii, 9 values per particle) and the masses, aggregate by aggregate
    /// (<paramref name="memberStart"/>, <paramref name="members"/>).
    /// </summary>
    public void Assemble(
        ILinearizableSystem system, double[] fineDiagonal, Span<double> masses, Span<double> inverseMasses, int count,
        CoarseLevel level, int[] memberStart, int[] members, IParallelRunner? runner)
    {
        var parts = runner is { MaxParallelism: > 1 } ? runner.MaxParallelism : 1;
        FilterTargets(inverseMasses, count, parts, level);
        fixed (double* fine = fineDiagonal, m = masses, w = inverseMasses)
        {
            _pass.Set(system, fine, m, w, count, level, memberStart, members, _targets);
            if (parts > 1)
            {
                runner!.Run(_pass, parts);
            }
            else
            {
                _pass.Execute(0, 1);
            }
        }
    }

    /// <summary>
    /// The level-1 targets of the couplings for each of <paramref name="parts"/> ranges of aggregates, without
    /// couplings that touch a pinned particle (rebuilt when pinning, the topology or the parts change).
    /// </summary>
    private void FilterTargets(Span<double> inverseMasses, int count, int parts, CoarseLevel level)
    {
        var particles = inverseMasses.Length;
        var same = _filteredFor.Length == particles;
        for (var i = 0; same && i < particles; i++)
        {
            same = _filteredFor[i] == (inverseMasses[i] == 0.0);
        }

        if (!same)
        {
            _filteredFor = new bool[particles];
            for (var i = 0; i < particles; i++)
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
            targets = FilteredTargets(count, parts, level);
        }

        _targets = targets;
    }

    private int[][] FilteredTargets(int count, int parts, CoarseLevel level)
    {
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
        private ILinearizableSystem? _system;
        private double* _fine;
        private double* _masses;
        private double* _inverseMasses;
        private int _count;
        private CoarseLevel? _level;
        private int[] _memberStart = Array.Empty<int>();
        private int[] _members = Array.Empty<int>();
        private int[][] _targets = Array.Empty<int[]>();

        /// <summary>
        /// Reads J_ii (<paramref name="fine"/>), the masses and the system's coupling blocks through
        /// <paramref name="targets"/> (forward and backward per part); writes <paramref name="level"/>'s blocks.
        /// </summary>
        public void Set(
            ILinearizableSystem system, double* fine, double* masses, double* inverseMasses, int count, CoarseLevel level,
            int[] memberStart, int[] members, int[][] targets)
        {
            _system = system;
            _fine = fine;
            _masses = masses;
            _inverseMasses = inverseMasses;
            _count = count;
            _level = level;
            _memberStart = memberStart;
            _members = members;
            _targets = targets;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var level = _level!;
            var (begin, end) = Chunk.Range(chunk, chunkCount, level.Count);
            var (first, last) = level.BlockRange(begin, end);
            Array.Clear(level.Values, 9 * first, 9 * (last - first)); // the diagonal blocks of the rows
            var (offFirst, offLast) = level.OffDiagonalRange(begin, end);
            Array.Clear(level.Values, 9 * offFirst, 9 * (offLast - offFirst));
            fixed (double* values = level.Values)
            fixed (int* memberStart = _memberStart, members = _members)
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

            _system!.AddCouplingBlocks(level.Values, _targets[2 * chunk].AsSpan(0, _count), _targets[(2 * chunk) + 1].AsSpan(0, _count));
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
}
