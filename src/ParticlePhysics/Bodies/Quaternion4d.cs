using System;
using System.Runtime.CompilerServices;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Bodies;

/// <summary>
/// A unit quaternion (w, x, y, z) for the step's own rotation arithmetic: products, rotating vectors, and the
/// exponential map of a rotation vector with <see cref="DeterministicTrig"/>, so that a body's orientation has the
/// same bits on every runtime (the public <see cref="Constraints.Rotation3d"/> uses Math.Sin and is for poses given
/// between steps).
/// </summary>
internal readonly struct Quaternion4d
{
    public Quaternion4d(double w, double x, double y, double z)
    {
        W = w;
        X = x;
        Y = y;
        Z = z;
    }

    public static Quaternion4d Identity => new(1.0, 0.0, 0.0, 0.0);

    public double W { get; }

    public double X { get; }

    public double Y { get; }

    public double Z { get; }

    /// <summary>The rotation a then b applied after it: b * a.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Quaternion4d operator *(Quaternion4d b, Quaternion4d a) => new(
        (b.W * a.W) - (b.X * a.X) - (b.Y * a.Y) - (b.Z * a.Z),
        (b.W * a.X) + (b.X * a.W) + (b.Y * a.Z) - (b.Z * a.Y),
        (b.W * a.Y) - (b.X * a.Z) + (b.Y * a.W) + (b.Z * a.X),
        (b.W * a.Z) + (b.X * a.Y) - (b.Y * a.X) + (b.Z * a.W));

    /// <summary>
    /// exp of the rotation vector <paramref name="theta"/> (axis times angle, rad): (cos(|theta|/2), sin(|theta|/2) theta
    /// / |theta|), with the series of sin(a/2)/a below 1e-4 rad where the quotient loses digits.
    /// </summary>
    public static Quaternion4d FromRotationVector(Vector3d theta)
    {
        var angle = theta.Length;
        double c, s;
        if (angle < 1e-4)
        {
            // sin(a/2)/a = 1/2 - a^2/48 + ..., cos(a/2) = 1 - a^2/8 + a^4/384: the next terms are below 1e-20.
            var a2 = angle * angle;
            s = 0.5 - (a2 / 48.0);
            c = 1.0 - (a2 / 8.0) + (a2 * a2 / 384.0);
        }
        else
        {
            s = DeterministicTrig.Sin(0.5 * angle) / angle;
            c = DeterministicTrig.Cos(0.5 * angle);
        }

        return new Quaternion4d(c, s * theta.X, s * theta.Y, s * theta.Z);
    }

    public static Quaternion4d FromRotation(Constraints.Rotation3d rotation) =>
        rotation.X == 0.0 && rotation.Y == 0.0 && rotation.Z == 0.0 ? Identity : new(rotation.W, rotation.X, rotation.Y, rotation.Z);

    public Constraints.Rotation3d ToRotation() => new(X, Y, Z, W);

    /// <summary>This divided by its length (the identity for a zero quaternion, which a step never makes).</summary>
    public Quaternion4d Normalized()
    {
        var norm = Math.Sqrt((W * W) + (X * X) + (Y * Y) + (Z * Z));
        return norm > 0.0 ? new Quaternion4d(W / norm, X / norm, Y / norm, Z / norm) : Identity;
    }

    /// <summary>q v q*, as v + 2 w (u x v) + 2 u x (u x v) with u the vector part.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public Vector3d Rotate(Vector3d v)
    {
        var u = new Vector3d(X, Y, Z);
        var t = 2.0 * Vector3d.Cross(u, v);
        return v + (W * t) + Vector3d.Cross(u, t);
    }

    /// <summary>q* v q: the inverse rotation of <paramref name="v"/>.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public Vector3d RotateInverse(Vector3d v)
    {
        var u = new Vector3d(-X, -Y, -Z);
        var t = 2.0 * Vector3d.Cross(u, v);
        return v + (W * t) + Vector3d.Cross(u, t);
    }
}
