using ParticlePhysics.Numerics;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Integrators;

/// <summary>
/// The passes before the iterations: the right-hand side b, the first residual r = b - A dv (from the warm start of
/// ConjugateGradientPasses.WarmStart.cs), and the inverted diagonal blocks of block Jacobi.
/// </summary>
internal sealed unsafe partial class ConjugateGradientPasses
{
    private readonly RightHandSidePass _rightHandSide = new();
    private readonly ResidualPass _residual = new();
    private readonly InvertBlocksPass _invertBlocks = new();

    /// <summary>b = h (f + h jw) on the free particles, 0 on pinned ones (jw = K v0), then jw = 0; returns b . b.</summary>
    public double RightHandSide(double[] force, double h)
    {
        CheckLength(force);
        fixed (double* f = force, jw = JacobianProduct, inverseMasses = _inverseMasses, b = B)
        {
            _rightHandSide.Set(f, jw, h, inverseMasses, b, _particles);
            Run(_rightHandSide);
        }

        return _rightHandSide.Sum();
    }

    /// <summary>
    /// r = b - (M dv - jw) on the free particles (jw = J dv, with the product's tail added first), 0 on pinned ones,
    /// then jw = 0; returns r . r.
    /// </summary>
    public double Residual()
    {
        fixed (double* dv = Dv, b = B, masses = _masses, inverseMasses = _inverseMasses, r = R, jw = JacobianProduct)
        {
            _residual.Set(dv, b, masses, inverseMasses, _hasTail, _tail, r, jw, _particles);
            Run(_residual);
        }

        return _residual.Sum();
    }

    /// <summary>
    /// Writes D_i^-1 = (M_i - J_ii)^-1 into <see cref="Inverses"/>; a pinned particle gets the zero block (filtered), a
    /// degenerate block plain Jacobi on the mass, 1 / m_i. <see cref="Blocks"/> keeps J_ii.
    /// </summary>
    public void InvertBlocks()
    {
        fixed (double* blocks = Blocks, masses = _masses, inverseMasses = _inverseMasses, inverses = _inverses)
        {
            _invertBlocks.Set(blocks, masses, inverseMasses, inverses, _particles);
            Run(_invertBlocks);
        }
    }

    /// <summary>b = h (f + h jw), then jw = 0, per chunk of particles; the chunks' b . b.</summary>
    private sealed class RightHandSidePass : IParallelWork
    {
        private readonly double[] _partial = new double[Chunks];
        private double* _force;
        private double* _jw;
        private double _h;
        private double* _inverseMasses;
        private double* _b;
        private int _particles;

        public void Set(double* force, double* jw, double h, double* inverseMasses, double* b, int particles)
        {
            _force = force;
            _jw = jw;
            _h = h;
            _inverseMasses = inverseMasses;
            _b = b;
            _particles = particles;
        }

        public double Sum() => Chunk.Sum(_partial);

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _particles);
            _partial[chunk] = OverRange(begin, end);
        }

        /// <summary>Particles [begin, end), 0 on pinned ones; returns their b . b.</summary>
        private double OverRange(int begin, int end)
        {
            double* b = _b, force = _force, jacobian = _jw, inverseMasses = _inverseMasses;
            var h = _h;
            var sum = 0.0;
            for (var i = begin; i < end; i++)
            {
                var o = 3 * i;
                double* bi = b + o, f = force + o, jw = jacobian + o;
                if (inverseMasses[i] == 0.0)
                {
                    bi[0] = bi[1] = bi[2] = 0.0;
                    jw[0] = jw[1] = jw[2] = 0.0;
                    continue;
                }

                bi[0] = h * (f[0] + (h * jw[0]));
                bi[1] = h * (f[1] + (h * jw[1]));
                bi[2] = h * (f[2] + (h * jw[2]));
                jw[0] = jw[1] = jw[2] = 0.0;
                sum += bi[0] * bi[0];
                sum += bi[1] * bi[1];
                sum += bi[2] * bi[2];
            }

            return sum;
        }
    }

    /// <summary>r = b - (M dv - jw), then jw = 0, per chunk of particles; the chunks' r . r.</summary>
    private sealed class ResidualPass : IParallelWork
    {
        private readonly double[] _partial = new double[Chunks];
        private double* _dv;
        private double* _b;
        private double* _masses;
        private double* _inverseMasses;
        private bool _hasTail;
        private double _tail;
        private double* _r;
        private double* _jw;
        private int _particles;

        public void Set(
            double* dv, double* b, double* masses, double* inverseMasses, bool hasTail, double tail, double* r, double* jw,
            int particles)
        {
            _dv = dv;
            _b = b;
            _masses = masses;
            _inverseMasses = inverseMasses;
            _hasTail = hasTail;
            _tail = tail;
            _r = r;
            _jw = jw;
            _particles = particles;
        }

        public double Sum() => Chunk.Sum(_partial);

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _particles);
            _partial[chunk] = OverRange(begin, end);
        }

        /// <summary>Particles [begin, end) (the tail added to jw first), 0 on pinned ones; returns their r . r.</summary>
        private double OverRange(int begin, int end)
        {
            double* dv = _dv, residual = _r, b = _b, jacobian = _jw, masses = _masses, inverseMasses = _inverseMasses;
            bool hasTail = _hasTail;
            var tail = _tail;
            var sum = 0.0;
            for (var i = begin; i < end; i++)
            {
                var o = 3 * i;
                double* x = dv + o, r = residual + o, bi = b + o, jw = jacobian + o;
                if (inverseMasses[i] == 0.0)
                {
                    r[0] = r[1] = r[2] = 0.0;
                    jw[0] = jw[1] = jw[2] = 0.0;
                    continue;
                }

                AddTail(jw, x, hasTail, tail);

                var m = masses[i];
                r[0] = bi[0] - ((m * x[0]) - jw[0]);
                r[1] = bi[1] - ((m * x[1]) - jw[1]);
                r[2] = bi[2] - ((m * x[2]) - jw[2]);
                jw[0] = jw[1] = jw[2] = 0.0;
                sum += r[0] * r[0];
                sum += r[1] * r[1];
                sum += r[2] * r[2];
            }

            return sum;
        }
    }

    /// <summary>D_i^-1 = (M_i - J_ii)^-1 per chunk of particles, as packed upper triangles.</summary>
    private sealed class InvertBlocksPass : IParallelWork
    {
        private double* _blocks;
        private double* _masses;
        private double* _inverseMasses;
        private double* _inverses;
        private int _particles;

        public void Set(double* blocks, double* masses, double* inverseMasses, double* inverses, int particles)
        {
            _blocks = blocks;
            _masses = masses;
            _inverseMasses = inverseMasses;
            _inverses = inverses;
            _particles = particles;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _particles);
            for (var i = begin; i < end; i++)
            {
                InvertBlock(i);
            }
        }

        /// <summary>
        /// D_i^-1 = (M_i - J_ii)^-1 for particle i, by the cofactors of the symmetric block (its upper triangle:
        /// <see cref="Blocks3.InvertSymmetric"/>), stored as its upper triangle.
        /// </summary>
        private void InvertBlock(int i)
        {
            var inverse = _inverses + (6L * i);
            if (_inverseMasses[i] == 0.0)
            {
                for (var k = 0; k < 6; k++)
                {
                    inverse[k] = 0.0;
                }

                return;
            }

            var m = _masses[i];
            var j = _blocks + (9L * i);
            if (!Blocks3.InvertSymmetric(m - j[0], -j[1], -j[2], m - j[4], -j[5], m - j[8], inverse))
            {
                // Degenerate block: fall back to plain Jacobi on the mass alone.
                inverse[0] = inverse[3] = inverse[5] = 1.0 / m;
                inverse[1] = inverse[2] = inverse[4] = 0.0;
            }
        }
    }
}
