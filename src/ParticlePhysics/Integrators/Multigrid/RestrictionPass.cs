using ParticlePhysics.Numerics;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Integrators.Multigrid;

/// <summary>
/// <see cref="AggregationMultigrid.Restrict"/> in fixed chunks of level-1 aggregates: B_I = sum of r_i over the free
/// members of aggregate I, in increasing member order, then X_I = D_I^-1 B_I when level 1 is smoothed (it is not the
/// coarsest).
/// </summary>
internal sealed unsafe class RestrictionPass : IParallelWork
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
