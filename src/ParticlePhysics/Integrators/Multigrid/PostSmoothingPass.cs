using ParticlePhysics.Parallel;

namespace ParticlePhysics.Integrators.Multigrid;

/// <summary>
/// A coarse level's post-smoothing X + D^-1 (B - A X) after its coarse correction, in chunks of its rows, fused with
/// the prolongation into the level above: each row's new X is added to its members there (X_above += P X). Each
/// row of the level above belongs to one aggregate, so the rows of a pass write disjoint members.
/// </summary>
internal sealed unsafe class PostSmoothingPass : IParallelWork
{
    private CoarseLevel? _level;
    private CoarseLevel? _above;

    /// <summary>
    /// Reads <paramref name="level"/>'s B, X and operator and writes its smoothed buffer (the rows still to come read
    /// the old X; the caller swaps the two after the pass); adds into <paramref name="above"/>'s X.
    /// </summary>
    public void Set(CoarseLevel level, CoarseLevel above)
    {
        _level = level;
        _above = above;
    }

    public void Execute(int chunk, int chunkCount)
    {
        CoarseLevel level = _level!, above = _above!;
        var (begin, end) = Chunk.Range(chunk, chunkCount, level.Count);
        fixed (double* b = level.B, x = level.X, smoothed = level.Smoothed, inverse = level.Inverse, values = level.Values)
        fixed (double* lanes = level.LaneBlocks, inverseLanes = level.LaneInverse)
        fixed (int* rowStart = level.RowStart, column = level.Column, split = level.Split, slot = level.Slot)
        fixed (double* aboveX = above.X)
        fixed (int* aboveStart = above.NextMemberStart, aboveMembers = above.NextMembers)
        {
            for (var i = begin; i < end; i++)
            {
                var c = smoothed + (3L * i);
                level.PostSmoothRow(i, values, rowStart, column, split, slot, b, x, inverse, lanes, inverseLanes, c);
                for (var m = aboveStart[i]; m < aboveStart[i + 1]; m++)
                {
                    var xm = aboveX + (3L * aboveMembers[m]);
                    xm[0] += c[0];
                    xm[1] += c[1];
                    xm[2] += c[2];
                }
            }
        }
    }
}
