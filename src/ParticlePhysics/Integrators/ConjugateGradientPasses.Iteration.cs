using ParticlePhysics.Integrators.Multigrid;
using ParticlePhysics.Numerics;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Integrators;

/// <summary>
/// The passes of one iteration: z . w after the product jw = J z, then the update of p, s, dv and r fused with the
/// preconditioner's first pass (block Jacobi's z = D^-1 r here, the multigrid's restriction in
/// <see cref="UpdateAndRestrict"/>), and the multigrid's second half.
/// </summary>
internal sealed unsafe partial class ConjugateGradientPasses
{
    private readonly MassMinusJacobianPass _massMinusJacobian = new();
    private readonly UpdateAndJacobiPass _updateAndJacobi = new();
    private readonly JacobiPass _jacobi = new();

    /// <summary>
    /// z . w with w = M z - jw on the free particles (jw = J z, with the product's tail added first and kept), jw = 0
    /// on the pinned ones (w is 0 there); the free particles' jw is left for the update, which computes w from it again
    /// and clears it.
    /// </summary>
    public double MassMinusJacobian()
    {
        fixed (double* z = Z, masses = _masses, inverseMasses = _inverseMasses, jw = JacobianProduct)
        {
            _massMinusJacobian.Set(z, masses, inverseMasses, _hasTail, _tail, jw, _particles);
            Run(_massMinusJacobian);
        }

        return _massMinusJacobian.Sum();
    }

    /// <summary>
    /// One step of the iteration and, for block Jacobi, its preconditioner: p = z + beta p, s = w + beta s (w = M z - jw,
    /// then jw = 0), dv += alpha p, r -= alpha s, then z = D^-1 r. Returns r . r; r . z is left in
    /// <see cref="LastJacobiProduct"/>.
    /// </summary>
    public double Update(double alpha, double beta)
    {
        fixed (double* z = Z, jw = JacobianProduct, masses = _masses, inverses = _inverses)
        fixed (double* p = P, s = S, dv = Dv, r = R)
        {
            _updateAndJacobi.Set(z, jw, masses, inverses, alpha, beta, p, s, dv, r, _particles);
            Run(_updateAndJacobi);
        }

        LastJacobiProduct = _updateAndJacobi.JacobiSum();
        return _updateAndJacobi.Sum();
    }

    /// <summary>z = D^-1 r with the inverted diagonal blocks; returns r . z.</summary>
    public double Jacobi()
    {
        fixed (double* r = R, inverses = _inverses, z = Z)
        {
            _jacobi.Set(r, inverses, z, _particles);
            Run(_jacobi);
        }

        return _jacobi.Sum();
    }

    /// <summary>
    /// The multigrid's first half on r, B_1 = P^T r with level 1's pre-smoothing (before the first iteration; see
    /// <see cref="AggregationMultigrid.Restrict"/>).
    /// </summary>
    public void Restrict(AggregationMultigrid multigrid) => multigrid.Restrict(R, _inverseMasses, _runner);

    /// <summary>
    /// One step of the iteration fused with the multigrid's first half on the new r
    /// (<see cref="AggregationMultigrid.UpdateAndRestrict"/>); returns r . r.
    /// </summary>
    public double UpdateAndRestrict(AggregationMultigrid multigrid, double alpha, double beta) =>
        multigrid.UpdateAndRestrict(Z, JacobianProduct, _masses, _coordinateMasses, P, S, Dv, R, _inverseMasses, alpha, beta, _runner);

    /// <summary>
    /// The multigrid's second half, z = D^-1 r + P X_1 after the cycle (<see cref="AggregationMultigrid.CycleAndProlong"/>);
    /// returns r . z.
    /// </summary>
    public double CycleAndProlong(AggregationMultigrid multigrid) => multigrid.CycleAndProlong(R, _inverses, _inverseMasses, Z, _runner);

    /// <summary>z . w with w = M z - jw per chunk of particles (the tail added to jw first and kept there).</summary>
    private sealed class MassMinusJacobianPass : IParallelWork
    {
        private readonly double[] _partial = new double[Chunks];
        private double* _z;
        private double* _masses;
        private double* _inverseMasses;
        private bool _hasTail;
        private double _tail;
        private double* _jw;
        private int _particles;

        public void Set(double* z, double* masses, double* inverseMasses, bool hasTail, double tail, double* jw, int particles)
        {
            _z = z;
            _masses = masses;
            _inverseMasses = inverseMasses;
            _hasTail = hasTail;
            _tail = tail;
            _jw = jw;
            _particles = particles;
        }

        public double Sum() => Chunk.Sum(_partial);

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _particles);
            _partial[chunk] = OverRange(begin, end);
        }

        /// <summary>Particles [begin, end), jw = 0 on pinned ones; returns their z . w.</summary>
        private double OverRange(int begin, int end)
        {
            double* preconditioned = _z, jacobian = _jw, masses = _masses, inverseMasses = _inverseMasses;
            bool hasTail = _hasTail;
            var tail = _tail;
            var sum = 0.0;
            for (var i = begin; i < end; i++)
            {
                var o = 3 * i;
                double* z = preconditioned + o, jw = jacobian + o;
                if (inverseMasses[i] == 0.0)
                {
                    jw[0] = jw[1] = jw[2] = 0.0; // (z is 0 here, so the update's w = M z - jw is 0)
                    continue;
                }

                AddTail(jw, z, hasTail, tail); // (kept in jw for the update)

                var m = masses[i];
                double wx = (m * z[0]) - jw[0], wy = (m * z[1]) - jw[1], wz = (m * z[2]) - jw[2];
                sum += (z[0] * wx) + (z[1] * wy) + (z[2] * wz);
            }

            return sum;
        }
    }

    /// <summary>
    /// The update (<see cref="ConjugateGradientUpdate"/>) fused with block Jacobi's z = D^-1 r per chunk of particles:
    /// the chunks' r . r and r . z.
    /// </summary>
    private sealed class UpdateAndJacobiPass : IParallelWork
    {
        private readonly double[] _partial = new double[Chunks];
        private readonly double[] _jacobiPartial = new double[Chunks];
        private double* _z;
        private double* _jw;
        private double* _masses;
        private double* _inverses;
        private double _alpha;
        private double _beta;
        private double* _p;
        private double* _s;
        private double* _dv;
        private double* _r;
        private int _particles;

        public void Set(
            double* z, double* jw, double* masses, double* inverses, double alpha, double beta, double* p, double* s,
            double* dv, double* r, int particles)
        {
            _z = z;
            _jw = jw;
            _masses = masses;
            _inverses = inverses;
            _alpha = alpha;
            _beta = beta;
            _p = p;
            _s = s;
            _dv = dv;
            _r = r;
            _particles = particles;
        }

        /// <summary>r . r after the update.</summary>
        public double Sum() => Chunk.Sum(_partial);

        /// <summary>r . z with the new z.</summary>
        public double JacobiSum() => Chunk.Sum(_jacobiPartial);

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _particles);
            _partial[chunk] = OverRange(begin, end, out _jacobiPartial[chunk]);
        }

        /// <summary>Particles [begin, end); returns their r . r, and r . z in <paramref name="rz"/>.</summary>
        private double OverRange(int begin, int end, out double rz)
        {
            double* z = _z, jw = _jw, p = _p, s = _s, dv = _dv, r = _r, inverses = _inverses, masses = _masses;
            double alpha = _alpha, beta = _beta;
            var sum = 0.0;
            var second = 0.0;
            for (var i = begin; i < end; i++)
            {
                var o = 3 * i;
                var mass = masses[i];
                var r0 = ConjugateGradientUpdate.Component(z, jw, mass, p, s, dv, r, alpha, beta, o);
                var r1 = ConjugateGradientUpdate.Component(z, jw, mass, p, s, dv, r, alpha, beta, o + 1);
                var r2 = ConjugateGradientUpdate.Component(z, jw, mass, p, s, dv, r, alpha, beta, o + 2);
                sum += r0 * r0;
                sum += r1 * r1;
                sum += r2 * r2;
                var zi = z + o;
                Blocks3.MultiplySymmetric(inverses + (6 * i), r + o, zi); // z = D^-1 r with the r just written
                second += (r0 * zi[0]) + (r1 * zi[1]) + (r2 * zi[2]);
            }

            rz = second;
            return sum;
        }
    }

    /// <summary>z = D^-1 r per chunk of particles; the chunks' r . z.</summary>
    private sealed class JacobiPass : IParallelWork
    {
        private readonly double[] _partial = new double[Chunks];
        private double* _r;
        private double* _inverses;
        private double* _z;
        private int _particles;

        public void Set(double* r, double* inverses, double* z, int particles)
        {
            _r = r;
            _inverses = inverses;
            _z = z;
            _particles = particles;
        }

        public double Sum() => Chunk.Sum(_partial);

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _particles);
            _partial[chunk] = OverRange(begin, end);
        }

        /// <summary>Particles [begin, end); returns their r . z.</summary>
        private double OverRange(int begin, int end)
        {
            double* residual = _r, preconditioned = _z, inverses = _inverses;
            var sum = 0.0;
            for (var i = begin; i < end; i++)
            {
                double* r = residual + (3 * i), z = preconditioned + (3 * i);
                Blocks3.MultiplySymmetric(inverses + (6 * i), r, z);
                sum += (r[0] * z[0]) + (r[1] * z[1]) + (r[2] * z[2]);
            }

            return sum;
        }
    }
}
