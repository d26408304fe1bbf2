using ParticlePhysics.Numerics;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Integrators.Multigrid;

/// <summary>
/// <see cref="AggregationMultigrid.UpdateAndRestrict"/> in the chunks of <see cref="RestrictionPass"/>: each chunk
/// updates its aggregates' members, then restricts their new r and sums their r . r. One pass rather than the update's
/// and the restriction's: a pass over the vectors and a hand-off fewer per iteration.
/// </summary>
internal sealed unsafe class UpdateAndRestrictionPass : IParallelWork
{
    private readonly double[] _partial = new double[AggregationMultigrid.Chunks];
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
