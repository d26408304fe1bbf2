using System;

namespace ParticlePhysics.Constraints;

/// <summary>
/// A rotation as a unit quaternion (x, y, z, w) in double precision, for the pose of a <see cref="KinematicBody"/>.
/// (Not named Quaternion, which would clash with UnityEngine.Quaternion; from Unity, pass q.x, q.y, q.z, q.w.)
/// </summary>
public readonly struct Rotation3d : IEquatable<Rotation3d>
{
    /// <summary>A rotation from quaternion components, normalised to unit length.</summary>
    /// <exception cref="ArgumentException">The components are not finite, or all zero.</exception>
    public Rotation3d(double x, double y, double z, double w)
    {
        var norm = Math.Sqrt((x * x) + (y * y) + (z * z) + (w * w));
        if (!(norm >= 1e-150) || double.IsInfinity(norm))
        {
            // Finite components whose squares overflow or underflow (1e200, 1e-200) are a rotation too: scale by the
            // largest first. A norm of ordinary size is divided by directly (one rounding fewer).
            var scale = Math.Max(Math.Max(Math.Abs(x), Math.Abs(y)), Math.Max(Math.Abs(z), Math.Abs(w)));
            if (!(scale > 0.0) || double.IsInfinity(scale) || double.IsNaN(x + y + z + w))
            {
                throw new ArgumentException(
                    $"A rotation needs finite quaternion components, not all zero; got ({Guard.Format(x)}, {Guard.Format(y)}, "
                    + $"{Guard.Format(z)}, {Guard.Format(w)}).");
            }

            (x, y, z, w) = (x / scale, y / scale, z / scale, w / scale);
            norm = Math.Sqrt((x * x) + (y * y) + (z * z) + (w * w));
        }

        X = x / norm;
        Y = y / norm;
        Z = z / norm;
        W = w / norm;
    }

    /// <summary>No rotation.</summary>
    public static Rotation3d Identity => new(0, 0, 0, 1);

    /// <summary>The x component of the unit quaternion.</summary>
    public double X { get; }

    /// <summary>The y component of the unit quaternion.</summary>
    public double Y { get; }

    /// <summary>The z component of the unit quaternion.</summary>
    public double Z { get; }

    /// <summary>The scalar component of the unit quaternion (1 for no rotation; a default value reads as no rotation too).</summary>
    public double W { get; }

    /// <summary>The rotation by <paramref name="angle"/> radians about <paramref name="axis"/> (right-handed).</summary>
    public static Rotation3d FromAxisAngle(Vector3d axis, double angle)
    {
        var length = axis.Length;
        if (!axis.IsFinite || (axis.X == 0.0 && axis.Y == 0.0 && axis.Z == 0.0) || double.IsNaN(angle) || double.IsInfinity(angle))
        {
            throw new ArgumentException(
                $"The axis must be finite and not zero, and the angle finite; got {axis} and {Guard.Format(angle)}.");
        }

        if (!(length >= 1e-150) || double.IsInfinity(length))
        {
            // An axis whose length overflows or underflows (1e300, 1e-200): its direction, from the scaled vector.
            axis = Guard.Direction(axis, nameof(axis));
            length = 1.0;
        }

        var s = Math.Sin(0.5 * angle) / length;
        return new Rotation3d(axis.X * s, axis.Y * s, axis.Z * s, Math.Cos(0.5 * angle));
    }

    /// <summary>Rotates <paramref name="v"/>: q v q*, as v + 2 w (q x v) + 2 q x (q x v) with q the vector part.</summary>
    public Vector3d Rotate(Vector3d v)
    {
        // default(Rotation3d) has w = 0 and a zero vector part: treat it as the identity rather than a collapse to 0.
        if (X == 0.0 && Y == 0.0 && Z == 0.0)
        {
            return v;
        }

        var q = new Vector3d(X, Y, Z);
        var t = 2.0 * Vector3d.Cross(q, v);
        return v + (W * t) + Vector3d.Cross(q, t);
    }

    /// <summary>The inverse rotation.</summary>
    public Rotation3d Inverse() => X == 0.0 && Y == 0.0 && Z == 0.0 ? Identity : new Rotation3d(-X, -Y, -Z, W);

    /// <inheritdoc />
    public bool Equals(Rotation3d other) => X.Equals(other.X) && Y.Equals(other.Y) && Z.Equals(other.Z) && W.Equals(other.W);

    /// <inheritdoc />
    public override bool Equals(object? obj) => obj is Rotation3d other && Equals(other);

    /// <inheritdoc />
    public override int GetHashCode() => HashCode.Combine(X, Y, Z, W);

    /// <summary>Equality of the components.</summary>
    public static bool operator ==(Rotation3d a, Rotation3d b) => a.Equals(b);

    /// <summary>Inequality of the components.</summary>
    public static bool operator !=(Rotation3d a, Rotation3d b) => !a.Equals(b);
}
