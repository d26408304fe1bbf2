using System;
using ParticlePhysics.Numerics;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Integrators.Multigrid;

/// <summary>
/// The next level's operator A_next = P^T A P from a coarse level's blocks: every block added where its row and
/// column aggregates meet, in chunks of the next level's aggregates.
/// </summary>
/// <remarks>
/// Row i's blocks all land in the row of its aggregate (its diagonal block, or a block right of it: a block whose
/// aggregates are in decreasing order is left to its mirror, which the next level stores), so each aggregate
/// assembles its own row from its members' rows, in increasing member order: every block gets its terms in
/// increasing row order, as a loop over all the rows gives them, whatever the chunks.
/// </remarks>
internal sealed unsafe class CoarseGalerkinPass : IParallelWork
{
    private CoarseLevel? _level;
    private CoarseLevel? _next;

    /// <summary>Reads <paramref name="level"/>'s blocks and link; writes <paramref name="next"/>'s blocks.</summary>
    public void Set(CoarseLevel level, CoarseLevel next)
    {
        _level = level;
        _next = next;
    }

    public void Execute(int chunk, int chunkCount)
    {
        CoarseLevel level = _level!, next = _next!;
        var (begin, end) = Chunk.Range(chunk, chunkCount, next.Count);
        fixed (double* values = level.Values, nextValues = next.Values)
        fixed (int* rowStart = level.RowStart, split = level.Split, slot = level.Slot, target = level.NextTarget)
        fixed (int* start = level.NextMemberStart, members = level.NextMembers)
        {
            GalerkinRows(level.Count, next, begin, end, values, nextValues, rowStart, split, slot, target, start, members);
        }
    }

    /// <summary>Aggregates [begin, end) of the next level's operator: their rows cleared, then summed.</summary>
    private static void GalerkinRows(
        int count, CoarseLevel next, int begin, int end, double* values, double* nextValues, int* rowStart, int* split,
        int* slot, int* target, int* start, int* members)
    {
        var (first, last) = next.BlockRange(begin, end);
        new Span<double>(nextValues + (9L * first), 9 * (last - first)).Clear();
        var (offFirst, offLast) = next.OffDiagonalRange(begin, end);
        new Span<double>(nextValues + (9L * offFirst), 9 * (offLast - offFirst)).Clear();
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
                        Blocks3.AddTransposed(nextValues + (9L * target[k]), values + (9L * (count + slot[k])));
                    }
                }

                for (var k = split[i]; k < rowStart[i + 1]; k++)
                {
                    if (target[k] >= 0)
                    {
                        Blocks3.Add(nextValues + (9L * target[k]), values + (9L * (count + slot[k])));
                    }
                }
            }
        }
    }
}
