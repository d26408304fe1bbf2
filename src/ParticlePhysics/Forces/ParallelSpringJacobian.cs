using System;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Forces;

/// <summary>
/// The spring network's linearisation over several threads, bit-identical to the sequential loops (as
/// <see cref="ParallelSpringForces"/> is for forces): each spring's 3-vectors go into their own slots, then each
/// particle gathers its springs' slots in increasing spring order (<see cref="SpringIncidence"/>). Diagonal blocks
/// need no slots: each particle adds its springs' blocks itself, in the same order. (The Jacobian product, run every
/// iteration, has a pass of its own without slots: <see cref="SpringJacobianProduct"/>.)
/// </summary>
internal sealed unsafe class ParallelSpringJacobian
{
    private readonly LinearizePass _linearize = new();
    private readonly BlocksPass _blocks = new();
    private readonly LinearizeWithForcesPass _linearizeWithForces = new();
    private readonly GatherAllPass _gatherAll = new();
    private double[] _perSpring = Array.Empty<double>();
    private double[] _perSpringForce = Array.Empty<double>();

    public void Linearize(
        double* x, double* v, double* parameters, int* first, int* second, int count, double positionScale,
        double velocityScale, double* linear, double* into, SpringIncidence incidence, IParallelRunner runner)
    {
        EnsureSlots(count);
        var chunks = 4 * runner.MaxParallelism;
        fixed (double* slots = _perSpring)
        {
            _linearize.Set(x, v, parameters, first, second, count, positionScale, velocityScale, linear, slots);
            runner.Run(_linearize, chunks);
            incidence.Gather(into, slots, firstEndAdds: true, runner, chunks);
        }
    }

    /// <summary>
    /// The forces, the linearisation and the diagonal blocks in two passes: each spring's force, (df/dx) dv and
    /// linearisation into its own slots, then each particle gathers its springs' force, product and block in increasing
    /// spring order (the same additions in the same order as the sequential loops).
    /// </summary>
    public void LinearizeWithForces(
        double* x, double* v, double* parameters, int* first, int* second, int count, double positionScale,
        double velocityScale, double* linear, double* forces, double* into, double* blocks, SpringIncidence incidence,
        IParallelRunner runner)
    {
        EnsureSlots(count);
        if (_perSpringForce.Length < 3 * count)
        {
            _perSpringForce = new double[3 * count];
        }

        var chunks = 4 * runner.MaxParallelism;
        fixed (double* slots = _perSpring, forceSlots = _perSpringForce)
        fixed (int* start = incidence.Start, incident = incidence.Incident)
        {
            _linearizeWithForces.Set(x, v, parameters, first, second, count, positionScale, velocityScale, linear, slots, forceSlots);
            runner.Run(_linearizeWithForces, chunks);
            _gatherAll.Set(forces, into, blocks, forceSlots, slots, linear, start, incident, incidence.Start.Length - 1);
            runner.Run(_gatherAll, chunks);
        }
    }

    public void DiagonalBlocks(double* blocks, double* linear, SpringIncidence incidence, IParallelRunner runner)
    {
        fixed (int* start = incidence.Start, incident = incidence.Incident)
        {
            _blocks.Set(blocks, linear, start, incident, incidence.Start.Length - 1);
            runner.Run(_blocks, 4 * runner.MaxParallelism);
        }
    }

    private void EnsureSlots(int count)
    {
        if (_perSpring.Length < 3 * count)
        {
            _perSpring = new double[3 * count];
        }
    }

    private sealed class LinearizePass : IParallelWork
    {
        private double* _x;
        private double* _v;
        private double* _parameters;
        private int* _first;
        private int* _second;
        private int _count;
        private double _positionScale;
        private double _velocityScale;
        private double* _linear;
        private double* _slots;

        public void Set(
            double* x, double* v, double* parameters, int* first, int* second, int count, double positionScale,
            double velocityScale, double* linear, double* slots)
        {
            _x = x;
            _v = v;
            _parameters = parameters;
            _first = first;
            _second = second;
            _count = count;
            _positionScale = positionScale;
            _velocityScale = velocityScale;
            _linear = linear;
            _slots = slots;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _count);
            for (var s = begin; s < end; s++)
            {
                var y = _slots + (3 * s);
                SpringLinearization.Pair(
                    _x, _v, 3L * _first[s], 3L * _second[s], _parameters + (3 * s), _positionScale, _velocityScale,
                    _linear + (5 * s), y);
            }
        }
    }

    private sealed class LinearizeWithForcesPass : IParallelWork
    {
        private double* _x;
        private double* _v;
        private double* _parameters;
        private int* _first;
        private int* _second;
        private int _count;
        private double _positionScale;
        private double _velocityScale;
        private double* _linear;
        private double* _slots;
        private double* _forceSlots;

        public void Set(
            double* x, double* v, double* parameters, int* first, int* second, int count, double positionScale,
            double velocityScale, double* linear, double* slots, double* forceSlots)
        {
            _x = x;
            _v = v;
            _parameters = parameters;
            _first = first;
            _second = second;
            _count = count;
            _positionScale = positionScale;
            _velocityScale = velocityScale;
            _linear = linear;
            _slots = slots;
            _forceSlots = forceSlots;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (first, last) = Chunk.Range(chunk, chunkCount, _count);
            var roots = stackalloc double[2 * SpringLengths.Block];
            for (var begin = first; begin < last; begin += SpringLengths.Block)
            {
                // Each block's lengths first, as the sequential loop takes them (SpringLengths).
                var end = Math.Min(last, begin + SpringLengths.Block);
                SpringLengths.Compute(_x, _first, _second, begin, end, roots);
                for (var s = begin; s < end; s++)
                {
                    SpringLinearization.PairWithForce(
                        _x, _v, 3L * _first[s], 3L * _second[s], _parameters + (3 * s), _positionScale, _velocityScale,
                        roots + (s - begin), _linear + (5 * s), _slots + (3 * s), _forceSlots + (3 * s));
                }
            }
        }
    }

    /// <summary>
    /// Per particle, in increasing spring order: the forces (subtracted at a first end, as the force loop does), the
    /// products (added at a first end) and the diagonal blocks.
    /// </summary>
    private sealed class GatherAllPass : IParallelWork
    {
        private double* _forces;
        private double* _into;
        private double* _blocks;
        private double* _forceSlots;
        private double* _slots;
        private double* _linear;
        private int* _start;
        private int* _incident;
        private int _particles;

        public void Set(
            double* forces, double* into, double* blocks, double* forceSlots, double* slots, double* linear, int* start,
            int* incident, int particles)
        {
            _forces = forces;
            _into = into;
            _blocks = blocks;
            _forceSlots = forceSlots;
            _slots = slots;
            _linear = linear;
            _start = start;
            _incident = incident;
            _particles = particles;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _particles);
            for (var i = begin; i < end; i++)
            {
                double* f = _forces + (3L * i), y = _into + (3L * i);
                double fx = f[0], fy = f[1], fz = f[2], yx = y[0], yy = y[1], yz = y[2];
                for (var e = _start[i]; e < _start[i + 1]; e++)
                {
                    var code = _incident[e];
                    var s = code >> 1;
                    double* sf = _forceSlots + (3L * s), sy = _slots + (3L * s);
                    if ((code & 1) == 0)
                    {
                        fx -= sf[0];
                        fy -= sf[1];
                        fz -= sf[2];
                        yx += sy[0];
                        yy += sy[1];
                        yz += sy[2];
                    }
                    else
                    {
                        fx += sf[0];
                        fy += sf[1];
                        fz += sf[2];
                        yx -= sy[0];
                        yy -= sy[1];
                        yz -= sy[2];
                    }

                }

                f[0] = fx;
                f[1] = fy;
                f[2] = fz;
                y[0] = yx;
                y[1] = yy;
                y[2] = yz;
            }

            SpringLinearization.GatherBlocks(_blocks, _linear, _start, _incident, begin, end);
        }
    }

    private sealed class BlocksPass : IParallelWork
    {
        private double* _blocks;
        private double* _linear;
        private int* _start;
        private int* _incident;
        private int _particles;

        public void Set(double* blocks, double* linear, int* start, int* incident, int particles)
        {
            _blocks = blocks;
            _linear = linear;
            _start = start;
            _incident = incident;
            _particles = particles;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _particles);
            SpringLinearization.GatherBlocks(_blocks, _linear, _start, _incident, begin, end);
        }
    }
}
