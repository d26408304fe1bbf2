using System;

namespace ParticlePhysics.Bodies;

/// <summary>
/// A body's inertia tensor in its own frame, I_0 = sum m (|d|^2 1 - d d^T) over its rest offsets d about their centre of
/// mass (symmetric: six values), and omega = I^-1 L for the body turned by R (I = R I_0 R^T), solved by cofactors.
/// </summary>
internal readonly struct RestInertia
{
    private readonly double _xx, _xy, _xz, _yy, _yz, _zz;

    private RestInertia(double xx, double xy, double xz, double yy, double yz, double zz)
    {
        (_xx, _xy, _xz, _yy, _yz, _zz) = (xx, xy, xz, yy, yz, zz);
    }

    /// <summary>The inertia of the offsets <paramref name="rest"/> - <paramref name="centre"/> with the masses m[particles[k]].</summary>
    public static RestInertia Of(Span<int> particles, Span<Vector3d> rest, Span<double> m, Vector3d centre)
    {
        double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
        for (var k = 0; k < rest.Length; k++)
        {
            var mi = m[particles[k]];
            var d = rest[k] - centre;
            double dx2 = d.X * d.X, dy2 = d.Y * d.Y, dz2 = d.Z * d.Z;
            xx += mi * (dy2 + dz2);
            yy += mi * (dx2 + dz2);
            zz += mi * (dx2 + dy2);
            xy -= mi * d.X * d.Y;
            xz -= mi * d.X * d.Z;
            yz -= mi * d.Y * d.Z;
        }

        return new RestInertia(xx, xy, xz, yy, yz, zz);
    }

    /// <summary>sum m |d|^2, half the trace: the size against which a determinant is small.</summary>
    public double SecondMoment => 0.5 * (_xx + _yy + _zz);

    /// <summary>det I_0 by the first row's cofactors.</summary>
    public double Determinant => (_xx * ((_yy * _zz) - (_yz * _yz))) + (_xy * ((_xz * _yz) - (_xy * _zz))) + (_xz * ((_xy * _yz) - (_xz * _yy)));

    /// <summary>omega = R I_0^-1 R^T L; 0 for a body with no inertia (one particle).</summary>
    public Vector3d AngularVelocity(Quaternion4d rotation, Vector3d momentum)
    {
        var b = rotation.RotateInverse(momentum);
        var c00 = (_yy * _zz) - (_yz * _yz);
        var c01 = (_xz * _yz) - (_xy * _zz);
        var c02 = (_xy * _yz) - (_xz * _yy);
        var det = (_xx * c00) + (_xy * c01) + (_xz * c02);
        if (!(det > 0.0))
        {
            return Vector3d.Zero;
        }

        var c11 = (_xx * _zz) - (_xz * _xz);
        var c12 = (_xy * _xz) - (_xx * _yz);
        var c22 = (_xx * _yy) - (_xy * _xy);
        var y = new Vector3d(
            ((c00 * b.X) + (c01 * b.Y) + (c02 * b.Z)) / det,
            ((c01 * b.X) + (c11 * b.Y) + (c12 * b.Z)) / det,
            ((c02 * b.X) + (c12 * b.Y) + (c22 * b.Z)) / det);
        return rotation.Rotate(y);
    }
}
