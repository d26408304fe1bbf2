using System;
using System.Collections.Generic;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Integrators.Multigrid;

/// <summary>
/// The hierarchy for the system's couplings: the graph of the couplings, its aggregation level by level (two pairwise
/// matchings per level, <see cref="CouplingGraph.PairTwice"/>) down to at most <see cref="CoarsestNodes"/> aggregates,
/// and the check, at each setup, that the couplings are the ones it was built for. It allocates, and runs only when
/// the topology changes.
/// </summary>
internal sealed partial class AggregationMultigrid
{
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
        _levels = Array.Empty<CoarseLevel>();

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

        var levels = new List<CoarseLevel>();
        var map = CouplingGraph.PairTwice(fine, out var coarseCount);
        var graph = fine.Contract(map, coarseCount);
        if (coarseCount > 0.9 * particles)
        {
            return; // hardly coupled: block Jacobi does as well
        }

        _aggregate = map;
        (_memberStart, _members) = CouplingGraph.Members(map, coarseCount);
        _chunkMembers = ContiguousChunkMembers(_memberStart, _members, coarseCount);
        var level = new CoarseLevel(graph);
        _fineAssembly.Link(_first, _second, count, map, level);
        levels.Add(level);
        while (level.Count > CoarsestNodes && levels.Count < MaxLevels)
        {
            var nextMap = CouplingGraph.PairTwice(graph, out var nextCount);
            if (nextCount > 0.9 * level.Count)
            {
                break;
            }

            graph = graph.Contract(nextMap, nextCount);
            var next = new CoarseLevel(graph);
            level.LinkTo(next, nextMap);
            levels.Add(next);
            level = next;
        }

        _levels = levels.ToArray();
    }
}
