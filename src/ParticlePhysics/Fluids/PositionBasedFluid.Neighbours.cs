using System;
using ParticlePhysics.Contacts;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Fluids;

// The fluid's buffers and its neighbour search: each substep gathers the fluid's particles into local arrays and lists
// the pairs closer than h, with the contact stage's grid over boxes of side h (two particles closer than h have
// overlapping boxes).
public sealed partial class PositionBasedFluid
{
    private readonly SpatialHashGrid _grid = new();
    private double[] _x = Array.Empty<double>();
    private double[] _saved = Array.Empty<double>();
    private double[] _min = Array.Empty<double>();
    private double[] _max = Array.Empty<double>();
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
        _min = new double[3 * capacity];
        _max = new double[3 * capacity];
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

    // Gathers the fluid's positions, masses and inverse masses, and lists the pairs closer than h.
    private void FindNeighbours(in ConstraintContext context)
    {
        var positions = context.Positions;
        var masses = context.Masses.ForReading();
        var inverse = context.InverseMasses.ForReading();
        var half = 0.5 * _kernel.Radius;
        for (var k = 0; k < _count; k++)
        {
            var p = _particles[k];
            _mass[k] = masses[p];
            _inverse[k] = inverse[p];
            for (var a = 0; a < 3; a++)
            {
                var x = positions[(3 * p) + a];
                _x[(3 * k) + a] = x;
                _min[(3 * k) + a] = x - half;
                _max[(3 * k) + a] = x + half;
            }
        }

        _grid.FindPairs(_min, _max, _count);
        var found = _grid.PairCount;
        if (_first.Length < found)
        {
            var capacity = Math.Max(found, 2 * _first.Length);
            _first = new int[capacity];
            _second = new int[capacity];
            _pairKernel = new double[capacity];
            _pairGradient = new double[3 * capacity];
        }

        var first = _grid.First.ForReading();
        var second = _grid.Second.ForReading();
        var h2 = _kernel.Radius * _kernel.Radius;
        _pairs = 0;
        for (var q = 0; q < found; q++)
        {
            int i = first[q], j = second[q];
            double dx = _x[3 * i] - _x[3 * j], dy = _x[(3 * i) + 1] - _x[(3 * j) + 1], dz = _x[(3 * i) + 2] - _x[(3 * j) + 2];
            if ((dx * dx) + (dy * dy) + (dz * dz) < h2)
            {
                _first[_pairs] = i;
                _second[_pairs] = j;
                _pairs++;
            }
        }
    }

    // The kernel and the gradient grad_i W_ij of every pair at the gathered positions.
    private void EvaluatePairs()
    {
        for (var q = 0; q < _pairs; q++)
        {
            int i = 3 * _first[q], j = 3 * _second[q];
            double dx = _x[i] - _x[j], dy = _x[i + 1] - _x[j + 1], dz = _x[i + 2] - _x[j + 2];
            var r2 = (dx * dx) + (dy * dy) + (dz * dz);
            _pairKernel[q] = _kernel.Density(r2);
            var f = -_kernel.GradientOverDistance(Math.Sqrt(r2));
            _pairGradient[3 * q] = f * dx;
            _pairGradient[(3 * q) + 1] = f * dy;
            _pairGradient[(3 * q) + 2] = f * dz;
        }
    }

    private void SaveGathered() => _x.AsSpan(0, 3 * _count).CopyTo(_saved);
}
