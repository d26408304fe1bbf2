using System;
using ParticlePhysics.Contacts;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Fluids;

// The fluid's buffers and its neighbour search: each substep gathers the fluid's particles into local arrays and lists
// the pairs closer than h (FluidNeighbours).
public sealed partial class PositionBasedFluid
{
    private readonly FluidNeighbours _neighbours = new();
    private double[] _x = Array.Empty<double>();
    private double[] _saved = Array.Empty<double>();
    private double[] _mass = Array.Empty<double>();
    private double[] _inverse = Array.Empty<double>();
    private double[] _density = Array.Empty<double>();
    private double[] _lambda = Array.Empty<double>();
    private double[] _squares = Array.Empty<double>();
    private double[] _gradient = Array.Empty<double>();
    private double[] _move = Array.Empty<double>();
    private double[] _v = Array.Empty<double>();
    private double[] _omega = Array.Empty<double>();
    private double[] _omegaNorm = Array.Empty<double>();
    private int[] _first = Array.Empty<int>();
    private int[] _second = Array.Empty<int>();
    private double[] _pairKernel = Array.Empty<double>();
    private double[] _pairGradient = Array.Empty<double>();
    private int _pairs;

    /// <summary>
    /// The density of every fluid particle (in the order of <see cref="Particles"/>), kg/m^3, as the last projection's
    /// last iteration found it before moving the particles (walls included).
    /// </summary>
    public ReadOnlySpan<double> Densities => _density.AsSpan(0, _count);

    /// <summary>The number of neighbour pairs (closer than h) the last substep found.</summary>
    public int PairCount => _pairs;

    private void Reserve(int count, int worldCount)
    {
        if (_localOf.Length < worldCount)
        {
            var old = _localOf.Length;
            Array.Resize(ref _localOf, Math.Max(worldCount, 2 * old));
            _localOf.AsSpan(old).Fill(-1);
        }

        if (_particles.Length >= count)
        {
            return;
        }

        var capacity = Math.Max(count, 2 * _particles.Length);
        Array.Resize(ref _particles, capacity);
        _x = new double[3 * capacity];
        _saved = new double[3 * capacity];
        _mass = new double[capacity];
        _inverse = new double[capacity];
        _density = new double[capacity];
        _lambda = new double[capacity];
        _squares = new double[capacity];
        _gradient = new double[3 * capacity];
        _move = new double[3 * capacity];
        _v = new double[3 * capacity];
        _omega = new double[3 * capacity];
        _omegaNorm = new double[capacity];
    }

    // Gathers the fluid's positions, masses and inverse masses, and lists the pairs closer than h and the walls.
    private void FindNeighbours(in ConstraintContext context)
    {
        var positions = context.Positions;
        var masses = context.Masses.ForReading();
        var inverse = context.InverseMasses.ForReading();
        for (var k = 0; k < _count; k++)
        {
            var p = _particles[k];
            _mass[k] = masses[p];
            _inverse[k] = inverse[p];
            _x[3 * k] = positions[3 * p];
            _x[(3 * k) + 1] = positions[(3 * p) + 1];
            _x[(3 * k) + 2] = positions[(3 * p) + 2];
        }

        FindWalls(context.Time + context.Dt);
        _neighbours.Find(_x, _count, _kernel.Radius);
        _pairs = _neighbours.Count;
        if (_pairKernel.Length < _pairs)
        {
            var capacity = Math.Max(_pairs, 2 * _pairKernel.Length);
            _pairKernel = new double[capacity];
            _pairGradient = new double[3 * capacity];
        }

        _first = _neighbours.First;
        _second = _neighbours.Second;
    }

    // The kernel and the gradient grad_i W_ij of every pair at the gathered positions.
    private void EvaluatePairs()
    {
        for (var q = 0; q < _pairs; q++)
        {
            int i = 3 * _first[q], j = 3 * _second[q];
            double dx = _x[i] - _x[j], dy = _x[i + 1] - _x[j + 1], dz = _x[i + 2] - _x[j + 2];
            var r2 = (dx * dx) + (dy * dy) + (dz * dz);
            var r = Math.Sqrt(r2);
            _pairKernel[q] = _kernel.Density(r);
            var f = -_kernel.GradientOverDistance(r);
            _pairGradient[3 * q] = f * dx;
            _pairGradient[(3 * q) + 1] = f * dy;
            _pairGradient[(3 * q) + 2] = f * dz;
        }
    }

    private void SaveGathered() => _x.AsSpan(0, 3 * _count).CopyTo(_saved);
}
