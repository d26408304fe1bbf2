using System;
using System.Runtime.InteropServices;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Forces;

/// <summary>
/// The spring network's forces over several threads, bit-identical to the sequential loop. The sequential loop
/// scatters spring s into both ends in increasing s; scattering from several threads would race and change the
/// order of the sums. So: pass 1 computes each spring's force vector into its own slot (independent), and pass 2
/// gives each particle the sum of its springs' forces, in increasing spring order, starting from the accumulator's
/// value: the same additions, in the same order, as the sequential loop (x - y equals x + (-y) exactly).
/// </summary>
internal sealed unsafe class ParallelSpringForces
{
    private readonly ComputePass _compute = new();
    private double[] _springForces = Array.Empty<double>();

    public SpringIncidence Incidence { get; } = new();

    public void AddForces(
        ForceElements pairs, int particleCount, ReadOnlySpan<double> x, ReadOnlySpan<double> v, Span<double> forces,
        IParallelRunner runner)
    {
        Incidence.Update(pairs, particleCount);
        if (_springForces.Length < 3 * pairs.Count)
        {
            _springForces = new double[3 * pairs.First.Length];
        }

        // Every pointer below stays inside its array: the buffers hold 3 values per particle (checked here), the
        // spring ends are below the particle count (checked when each spring was added), the per-spring slots and the
        // incidence were sized for these springs and particles (just above).
        var needed = 3 * particleCount;
        if (x.Length < needed || v.Length < needed || forces.Length < needed || pairs.Parameters.Length < 3 * pairs.Count)
        {
            throw new ArgumentException(
                $"The parallel spring pass needs buffers of {needed} values; got {x.Length}, {v.Length} and {forces.Length}.");
        }

        var chunks = 4 * runner.MaxParallelism;
        fixed (double* xp = &MemoryMarshal.GetReference(x), vp = &MemoryMarshal.GetReference(v), fp = forces, sf = _springForces, parameters = pairs.Parameters)
        fixed (int* first = pairs.First, second = pairs.Second)
        {
            _compute.Set(xp, vp, sf, parameters, first, second, pairs.Count);
            runner.Run(_compute, chunks);
            Incidence.Gather(fp, sf, firstEndAdds: false, runner, chunks);
        }
    }

    /// <summary>Pass 1: each spring's force on its first end, F = -(k (l - L) + c (dv . u)) u, as in the sequential loop.</summary>
    private sealed class ComputePass : IParallelWork
    {
        private double* _x;
        private double* _v;
        private double* _springForces;
        private double* _parameters;
        private int* _first;
        private int* _second;
        private int _count;

        public void Set(double* x, double* v, double* springForces, double* parameters, int* first, int* second, int count)
        {
            _x = x;
            _v = v;
            _springForces = springForces;
            _parameters = parameters;
            _first = first;
            _second = second;
            _count = count;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _count);
            double* x = _x, v = _v;
            for (var s = begin; s < end; s++)
            {
                long a = 3 * _first[s], b = 3 * _second[s];
                double* xa = x + a, xb = x + b, va = v + a, vb = v + b;
                var q = _parameters + (3 * s);
                var f = _springForces + (3 * s);
                double dx = xa[0] - xb[0], dy = xa[1] - xb[1], dz = xa[2] - xb[2];
                var lengthSquared = (dx * dx) + (dy * dy) + (dz * dz);
                if (lengthSquared == 0.0)
                {
                    // No direction, no force: the sequential loop adds the same zero.
                    f[0] = f[1] = f[2] = 0.0;
                    continue;
                }

                var length = Math.Sqrt(lengthSquared);
                var inverse = 1.0 / length;
                double ux = dx * inverse, uy = dy * inverse, uz = dz * inverse;
                var closing = ((va[0] - vb[0]) * ux) + ((va[1] - vb[1]) * uy) + ((va[2] - vb[2]) * uz);
                var magnitude = (q[0] * (length - q[1])) + (q[2] * closing);
                f[0] = magnitude * ux;
                f[1] = magnitude * uy;
                f[2] = magnitude * uz;
            }
        }
    }
}
