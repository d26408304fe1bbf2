using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics;

/// <summary>
/// Linearises a force generator that has no Jacobian of its own, by directional finite differences:
/// (a df/dx + b df/dv) w ~ (F(x0 + e a w, v0 + e b w) - F(x0, v0)) / e, one evaluation of that generator per
/// product. It offers no diagonal blocks, so the preconditioner sees only the other forces for it.
/// </summary>
internal sealed class FiniteDifferenceJacobian : IForceJacobian
{
    private const double RootEpsilon = 1.4901161193847656e-8;
    private readonly IForceGenerator _generator;
    private double[] _x = Array.Empty<double>();
    private double[] _v = Array.Empty<double>();
    private double[] _masses = Array.Empty<double>();
    private double[] _inverseMasses = Array.Empty<double>();
    private double[] _base = Array.Empty<double>();
    private double[] _shiftedX = Array.Empty<double>();
    private double[] _shiftedV = Array.Empty<double>();
    private double[] _shifted = Array.Empty<double>();
    private double _time;
    private double _positionScale;
    private double _velocityScale;
    private double _stateScale;

    public FiniteDifferenceJacobian(IForceGenerator generator)
    {
        _generator = generator;
    }

    public void Linearize(
        in ParticleState state, double positionScale, double velocityScale, Span<double> positionJacobianTimesVelocity)
    {
        var n = state.Positions.Length;
        if (_x.Length != n)
        {
            _x = new double[n];
            _v = new double[n];
            _base = new double[n];
            _shiftedX = new double[n];
            _shiftedV = new double[n];
            _shifted = new double[n];
            _masses = new double[n / 3];
            _inverseMasses = new double[n / 3];
        }

        state.Positions.CopyTo(_x);
        state.Velocities.CopyTo(_v);
        state.Masses.CopyTo(_masses);
        state.InverseMasses.CopyTo(_inverseMasses);
        _time = state.Time;
        _positionScale = positionScale;
        _velocityScale = velocityScale;
        _stateScale = 1.0;
        for (var k = 0; k < n; k++)
        {
            _stateScale = Math.Max(_stateScale, Math.Max(Math.Abs(_x[k]), Math.Abs(_v[k])));
        }

        Array.Clear(_base, 0, n);
        _generator.AddForces(new ParticleState(_time, _x, _v, _masses, _inverseMasses), _base);

        // (df/dx) v0: a directional difference along (v0, 0).
        Directional(_v, 1.0, 0.0, positionJacobianTimesVelocity);
    }

    public void AddJacobianProduct(ReadOnlySpan<double> w, Span<double> result) =>
        Directional(w, _positionScale, _velocityScale, result);

    public void AddDiagonalBlocks(Span<double> blocks)
    {
        // Unknown: the preconditioner does without this force's diagonal.
    }

    private void Directional(ReadOnlySpan<double> w, double a, double b, Span<double> result)
    {
        if (w.Length != _x.Length || result.Length != _x.Length)
        {
            throw new InvalidOperationException(
                $"The finite-difference Jacobian was linearised over {_x.Length} values; a product of {w.Length} into "
                + $"{result.Length} needs a Linearize at the current world first.");
        }

        var wr = w.ForReading();
        var size = 0.0;
        for (var k = 0; k < w.Length; k++)
        {
            size = Math.Max(size, Math.Max(Math.Abs(a * wr[k]), Math.Abs(b * wr[k])));
        }

        if (size == 0.0)
        {
            return;
        }

        var e = RootEpsilon * _stateScale / size;
        for (var k = 0; k < w.Length; k++)
        {
            _shiftedX[k] = _x[k] + (e * a * wr[k]);
            _shiftedV[k] = _v[k] + (e * b * wr[k]);
        }

        Array.Clear(_shifted, 0, _shifted.Length);
        _generator.AddForces(new ParticleState(_time, _shiftedX, _shiftedV, _masses, _inverseMasses), _shifted);
        for (var k = 0; k < w.Length; k++)
        {
            result[k] += (_shifted[k] - _base[k]) / e;
        }
    }
}
