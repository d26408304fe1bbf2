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

    /// <summary>
    /// J w added into y in one pass over the particles: each particle takes its springs in increasing spring order and
    /// computes each one's share (s I + t u u^T)(w_a - w_b) itself, adding it at a first end and subtracting it at a
    /// second. A spring's share is computed twice, once at each end, by the same operations, and each particle's sums
    /// are those of the sequential loop in the same order (the same bits), with one hand-off and no per-spring slots
    /// to write and read back.
    /// </summary>
    public void Product(double* w, double* y, double* linear, int* first, int* second, SpringIncidence incidence, IParallelRunner runner)
    {
        fixed (int* start = incidence.Start, incident = incidence.Incident)
        {
            _product.Set(w, y, linear, first, second, start, incident, incidence.Start.Length - 1);
            runner.Run(_product, 4 * runner.MaxParallelism);
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
            var (begin, end) = Chunk.Range(chunk, chunkCount, _count);
            for (var s = begin; s < end; s++)
            {
                SpringLinearization.PairWithForce(
                    _x, _v, 3L * _first[s], 3L * _second[s], _parameters + (3 * s), _positionScale, _velocityScale,
                    _linear + (5 * s), _slots + (3 * s), _forceSlots + (3 * s));
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

    private sealed class ProductPass : IParallelWork
    {
        private double* _w;
        private double* _y;
        private double* _linear;
        private int* _first;
        private int* _second;
        private int* _start;
        private int* _incident;
        private int _particles;

        public void Set(double* w, double* y, double* linear, int* first, int* second, int* start, int* incident, int particles)
        {
            _w = w;
            _y = y;
            _linear = linear;
            _first = first;
            _second = second;
            _start = start;
            _incident = incident;
            _particles = particles;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _particles);
            for (var i = begin; i < end; i++)
            {
                var yi = _y + (3L * i);
                double yx = yi[0], yy = yi[1], yz = yi[2];
                for (var e = _start[i]; e < _start[i + 1]; e++)
                {
                    // The spring's share (s I + t u u^T)(w_a - w_b) at its first end, as SpringNetwork.AddJacobianProduct's loop computes it.
                    var code = _incident[e];
                    var s = code >> 1;
                    double* wa = _w + (3L * _first[s]), wb = _w + (3L * _second[s]), q = _linear + (5L * s);
                    double dx = wa[0] - wb[0], dy = wa[1] - wb[1], dz = wa[2] - wb[2];
                    double ux = q[0], uy = q[1], uz = q[2], iso = q[3];
                    var axial = q[4] * ((ux * dx) + (uy * dy) + (uz * dz));
                    double px = (iso * dx) + (axial * ux), py = (iso * dy) + (axial * uy), pz = (iso * dz) + (axial * uz);
                    if ((code & 1) == 0)
                    {
                        yx += px;
                        yy += py;
                        yz += pz;
                    }
                    else
                    {
                        yx -= px;
                        yy -= py;
                        yz -= pz;
                    }
                }

                yi[0] = yx;
                yi[1] = yy;
                yi[2] = yz;
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
            SpringLinearization.GatherBlocks(_blocks, _linear, _start, _incident, begin, end);
        }
    }
}
