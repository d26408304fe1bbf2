using System;
using System.Runtime.InteropServices;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Integrators;

/// <summary>
/// The passes after the iterations: the product q = b - r that the next step's warm start reads, and the end state
/// v1 = v0 + dv, x1 = x0 + h v1.
/// </summary>
internal sealed unsafe partial class ConjugateGradientPasses
{
    private readonly SolutionProductPass _solutionProduct = new();
    private readonly EndStatePass _endState = new();

    /// <summary>q = b - r on the free particles, 0 on pinned ones: A dv for the solution just found, up to the solve's residual.</summary>
    public void SolutionProduct(double[] product)
    {
        CheckLength(product);
        fixed (double* b = B, r = R, inverseMasses = _inverseMasses, q = product)
        {
            _solutionProduct.Set(b, r, inverseMasses, q, _particles);
            Run(_solutionProduct);
        }
    }

    /// <summary>v1 = v0 + dv and x1 = x0 + h v1, for every particle (a pinned one moves at its own velocity).</summary>
    public void EndState(ReadOnlySpan<double> x0, ReadOnlySpan<double> v0, Span<double> x1, Span<double> v1, double h)
    {
        var n = 3L * _particles;
        if (x0.Length < n || v0.Length < n || x1.Length < n || v1.Length < n)
        {
            throw new ArgumentException($"The end state needs {n} positions and velocities.");
        }

        fixed (double* px0 = &MemoryMarshal.GetReference(x0), pv0 = &MemoryMarshal.GetReference(v0))
        fixed (double* dv = Dv, px1 = x1, pv1 = v1)
        {
            _endState.Set(px0, pv0, dv, h, px1, pv1, _particles);
            Run(_endState);
        }
    }

    /// <summary>q = b - r per chunk of particles, 0 on pinned ones.</summary>
    private sealed class SolutionProductPass : IParallelWork
    {
        private double* _b;
        private double* _r;
        private double* _inverseMasses;
        private double* _q;
        private int _particles;

        public void Set(double* b, double* r, double* inverseMasses, double* q, int particles)
        {
            _b = b;
            _r = r;
            _inverseMasses = inverseMasses;
            _q = q;
            _particles = particles;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _particles);
            OverRange(begin, end);
        }

        private void OverRange(int begin, int end)
        {
            double* q = _q, b = _b, r = _r, inverseMasses = _inverseMasses;
            for (var k = 3 * begin; k < 3 * end; k++)
            {
                q[k] = inverseMasses[k / 3] == 0.0 ? 0.0 : b[k] - r[k];
            }
        }
    }

    /// <summary>v1 = v0 + dv and x1 = x0 + h v1 per chunk of particles.</summary>
    private sealed class EndStatePass : IParallelWork
    {
        private double* _x0;
        private double* _v0;
        private double* _dv;
        private double _h;
        private double* _x1;
        private double* _v1;
        private int _particles;

        public void Set(double* x0, double* v0, double* dv, double h, double* x1, double* v1, int particles)
        {
            _x0 = x0;
            _v0 = v0;
            _dv = dv;
            _h = h;
            _x1 = x1;
            _v1 = v1;
            _particles = particles;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _particles);
            OverRange(begin, end);
        }

        private void OverRange(int begin, int end)
        {
            double* x0 = _x0, v0 = _v0, x1 = _x1, v1 = _v1, dv = _dv;
            var h = _h;
            for (var k = 3 * begin; k < 3 * end; k++)
            {
                var v = v0[k] + dv[k];
                v1[k] = v;
                x1[k] = x0[k] + (h * v);
            }
        }
    }
}
