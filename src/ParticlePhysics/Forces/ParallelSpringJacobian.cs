using System;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Forces;

/// <summary>
/// The spring network's linearisation and Jacobian products over several threads, bit-identical to the sequential
/// loops (as <see cref="ParallelSpringForces"/> is for forces): each spring's 3-vector goes into its own slot, then
/// each particle gathers its springs' slots in increasing spring order (<see cref="SpringIncidence"/>). Diagonal
/// blocks need no slots: each particle adds its springs' blocks itself, in the same order.
/// </summary>
internal sealed unsafe class ParallelSpringJacobian
{
    private readonly LinearizePass _linearize = new();
    private readonly ProductPass _product = new();
    private readonly BlocksPass _blocks = new();
    private double[] _perSpring = Array.Empty<double>();

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

    public void Product(double* w, double* y, double* linear, int* first, int* second, int count, SpringIncidence incidence, IParallelRunner runner)
    {
        EnsureSlots(count);
        var chunks = 4 * runner.MaxParallelism;
        fixed (double* slots = _perSpring)
        {
            _product.Set(w, linear, first, second, count, slots);
            runner.Run(_product, chunks);
            incidence.Gather(y, slots, firstEndAdds: true, runner, chunks);
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

    private sealed class ProductPass : IParallelWork
    {
        private double* _w;
        private double* _linear;
        private int* _first;
        private int* _second;
        private int _count;
        private double* _slots;

        public void Set(double* w, double* linear, int* first, int* second, int count, double* slots)
        {
            _w = w;
            _linear = linear;
            _first = first;
            _second = second;
            _count = count;
            _slots = slots;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _count);
            for (var s = begin; s < end; s++)
            {
                var y = _slots + (3 * s);
                SpringLinearization.Product(_w, 3L * _first[s], 3L * _second[s], _linear + (5 * s), y);
            }
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
            for (var i = begin; i < end; i++)
            {
                var block = _blocks + (9L * i);
                for (var e = _start[i]; e < _start[i + 1]; e++)
                {
                    SpringLinearization.AddBlock(block, _linear + (5 * (_incident[e] >> 1)));
                }
            }
        }
    }
}
