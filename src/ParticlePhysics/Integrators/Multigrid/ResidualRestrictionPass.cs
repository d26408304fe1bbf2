using System.Numerics;
using ParticlePhysics.Numerics;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Integrators.Multigrid;

/// <summary>
/// The next level's right-hand side B_next = P^T (B - A X) from a coarse level whose pre-smoothing X = D^-1 B is done,
/// and when asked the next level's own pre-smoothing from zero, X_next = D_next^-1 B_next: in chunks of the next
/// level's aggregates, each summing its members' residual rows in increasing member order.
/// </summary>
internal sealed unsafe class ResidualRestrictionPass : IParallelWork
{
    private CoarseLevel? _level;
    private CoarseLevel? _next;
    private bool _smoothNext;

    /// <summary>
    /// Reads <paramref name="level"/>'s B, X and operator; writes <paramref name="next"/>'s B, and its X when
    /// <paramref name="smoothNext"/> (it is not the coarsest, whose X the direct solve writes).
    /// </summary>
    public void Set(CoarseLevel level, CoarseLevel next, bool smoothNext)
    {
        _level = level;
        _next = next;
        _smoothNext = smoothNext;
    }

    public void Execute(int chunk, int chunkCount)
    {
        CoarseLevel level = _level!, next = _next!;
        var (begin, end) = Chunk.Range(chunk, chunkCount, next.Count);
        fixed (double* b = level.B, x = level.X, values = level.Values, lanes = level.LaneBlocks)
        fixed (int* rowStart = level.RowStart, column = level.Column, split = level.Split, slot = level.Slot)
        fixed (double* nextB = next.B, nextX = next.X, nextInverse = next.Inverse)
        fixed (int* start = level.NextMemberStart, members = level.NextMembers)
        {
            for (var a = begin; a < end; a++)
            {
                double b0 = 0.0, b1 = 0.0, b2 = 0.0;
                if (CoarseLevel.Lanes)
                {
                    var sum = Vector<double>.Zero; // the members' residual rows added lane by lane, in member order
                    for (var k = start[a]; k < start[a + 1]; k++)
                    {
                        sum += CoarseLevel.ResidualLanes(members[k], lanes, rowStart, column, b, x);
                    }

                    (b0, b1, b2) = (sum[0], sum[1], sum[2]);
                }
                else
                {
                    for (var k = start[a]; k < start[a + 1]; k++)
                    {
                        var r = level.ResidualRow(members[k], values, rowStart, column, split, slot, b, x); // member k's residual row
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
}
