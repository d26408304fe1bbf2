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
    private readonly GatherPass _gather = new();
    private double[] _springForces = Array.Empty<double>();

    // Incidence (compressed rows): for particle i, entries _start[i].._start[i + 1] - 1 of _incident hold its
    // springs in increasing order, encoded as 2 s for a first end (subtract) and 2 s + 1 for a second end (add).
    private int[] _start = Array.Empty<int>();
    private int[] _incident = Array.Empty<int>();
    private int _indexedSprings = -1;
    private int _indexedParticles = -1;

    public void AddForces(
        ForceElements pairs, int particleCount, ReadOnlySpan<double> x, ReadOnlySpan<double> v, Span<double> forces,
        IParallelRunner runner)
    {
        if (_indexedSprings != pairs.Count || _indexedParticles != particleCount)
        {
            BuildIncidence(pairs, particleCount);
        }

        if (_springForces.Length < 3 * pairs.Count)
        {
            _springForces = new double[3 * pairs.First.Length];
        }

        var chunks = 4 * runner.MaxParallelism;
        fixed (double* xp = &MemoryMarshal.GetReference(x), vp = &MemoryMarshal.GetReference(v), fp = forces, sf = _springForces, parameters = pairs.Parameters)
        fixed (int* first = pairs.First, second = pairs.Second, start = _start, incident = _incident)
        {
            _compute.Set(xp, vp, sf, parameters, first, second, pairs.Count);
            runner.Run(_compute, chunks);
            _gather.Set(fp, sf, start, incident, particleCount);
            runner.Run(_gather, chunks);
        }
    }

    private void BuildIncidence(ForceElements pairs, int particleCount)
    {
        var start = new int[particleCount + 1];
        for (var s = 0; s < pairs.Count; s++)
        {
            start[pairs.First[s] + 1]++;
            start[pairs.Second[s] + 1]++;
        }

        for (var i = 0; i < particleCount; i++)
        {
            start[i + 1] += start[i];
        }

        var incident = new int[2 * pairs.Count];
        var fill = (int[])start.Clone();
        for (var s = 0; s < pairs.Count; s++)
        {
            incident[fill[pairs.First[s]]++] = 2 * s;
            incident[fill[pairs.Second[s]]++] = (2 * s) + 1;
        }

        _start = start;
        _incident = incident;
        _indexedSprings = pairs.Count;
        _indexedParticles = particleCount;
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

    /// <summary>Pass 2: each particle adds its springs' forces in increasing spring order.</summary>
    private sealed class GatherPass : IParallelWork
    {
        private double* _forces;
        private double* _springForces;
        private int* _start;
        private int* _incident;
        private int _particles;

        public void Set(double* forces, double* springForces, int* start, int* incident, int particles)
        {
            _forces = forces;
            _springForces = springForces;
            _start = start;
            _incident = incident;
            _particles = particles;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _particles);
            for (var i = begin; i < end; i++)
            {
                var f = _forces + (3 * i);
                double fx = f[0], fy = f[1], fz = f[2];
                for (var e = _start[i]; e < _start[i + 1]; e++)
                {
                    var code = _incident[e];
                    var sf = _springForces + (3 * (code >> 1));
                    if ((code & 1) == 0)
                    {
                        fx -= sf[0];
                        fy -= sf[1];
                        fz -= sf[2];
                    }
                    else
                    {
                        fx += sf[0];
                        fy += sf[1];
                        fz += sf[2];
                    }
                }

                f[0] = fx;
                f[1] = fy;
                f[2] = fz;
            }
        }
    }
}
