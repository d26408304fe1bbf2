using System;
using System.Runtime.CompilerServices;
using ParticlePhysics.Numerics;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Integrators.Multigrid;

/// <summary>
/// A coarse level's diagonal blocks inverted into <see cref="CoarseLevel.Inverse"/>, D^-1 for its smoothing sweeps,
/// in chunks of its rows; a zero block (an aggregate of pinned particles only) becomes the identity, and a singular
/// one the inverse of its diagonal. On the lanes path each row's blocks are then copied by columns
/// (<see cref="CoarseLevel.LaneBlocks"/>, <see cref="CoarseLevel.LaneInverse"/>).
/// </summary>
internal sealed unsafe class BlockInversionPass : IParallelWork
{
    private CoarseLevel? _level;

    public void Set(CoarseLevel level) => _level = level;

    public void Execute(int chunk, int chunkCount)
    {
        var level = _level!;
        var (begin, end) = Chunk.Range(chunk, chunkCount, level.Count);
        var d = level.Values;
        var inverse = level.Inverse;
        for (var i = begin; i < end; i++)
        {
            var o = 9 * i;
            if (d[o] == 0.0 && d[o + 4] == 0.0 && d[o + 8] == 0.0)
            {
                d[o] = d[o + 4] = d[o + 8] = 1.0;
            }

            if (!Blocks3.Invert(d, o, inverse, o))
            {
                Array.Clear(inverse, o, 9);
                inverse[o] = 1.0 / Math.Max(d[o], double.Epsilon);
                inverse[o + 4] = 1.0 / Math.Max(d[o + 4], double.Epsilon);
                inverse[o + 8] = 1.0 / Math.Max(d[o + 8], double.Epsilon);
            }
        }

        if (CoarseLevel.Lanes)
        {
            fixed (double* values = level.Values, inverses = level.Inverse, lanes = level.LaneBlocks, inverseLanes = level.LaneInverse)
            {
                for (var i = begin; i < end; i++)
                {
                    LaneRow(level, i, values, inverses, lanes, inverseLanes);
                }
            }
        }
    }

    /// <summary>
    /// Row i's blocks and inverted diagonal block by columns for the lanes path: the diagonal block and each entry's
    /// block A_ij, a block right of the diagonal transposed from its row-major storage, one left of it copied as it
    /// is (its storage is A_ji = A_ij^T row by row, which is A_ij column by column).
    /// </summary>
    private static void LaneRow(CoarseLevel level, int i, double* values, double* inverse, double* lanes, double* inverseLanes)
    {
        int[] rowStart = level.RowStart, slot = level.Slot, split = level.Split;
        var count = level.Count;
        var k = rowStart[i];
        Transpose(values + (9L * i), lanes + (9L * (i + k)));
        Transpose(inverse + (9L * i), inverseLanes + (9L * i));
        for (; k < rowStart[i + 1]; k++)
        {
            double* stored = values + (9L * (count + slot[k])), to = lanes + (9L * (i + 1 + k));
            if (k < split[i])
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
}
