using ParticlePhysics.Parallel;

namespace ParticlePhysics.Integrators.Multigrid;

/// <summary>
/// The end of <see cref="AggregationMultigrid.CycleAndProlong"/> in the chunks of <see cref="RestrictionPass"/>: level
/// 1's post-smoothing of the chunk's aggregates (when level 1 is not the coarsest), then z_i = D_i^-1 r_i + X_1[a] on
/// their free members and 0 on pinned ones, and the chunk's r . z.
/// </summary>
internal sealed unsafe class PostSmoothAndProlongPass : IParallelWork
{
    private readonly double[] _partial = new double[AggregationMultigrid.Chunks];
    private double* _r;
    private double* _inverses;
    private double* _inverseMasses;
    private int* _memberStart;
    private int* _members;
    private int _aggregates;
    private CoarseLevel? _level;
    private double* _coarseX;
    private double* _z;

    /// <summary>
    /// <paramref name="level"/>: level 1 when its post-smoothing is fused here (it writes the new X_1 into
    /// <paramref name="coarseX"/>, its smoothed buffer), null when X_1 is final (the coarsest solve's, in
    /// <paramref name="coarseX"/>).
    /// </summary>
    public void Set(
        double* r, double* inverses, double* inverseMasses, int* memberStart, int* members, int aggregates, CoarseLevel? level,
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
    /// The addresses in locals: a field is loaded again after every store through a pointer.
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
