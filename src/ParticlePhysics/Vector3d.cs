using System;
using System.Globalization;
using System.Numerics;
using System.Runtime.CompilerServices;
using ParticlePhysics.Numerics;

namespace ParticlePhysics;

/// <summary>
/// A 3D vector in double precision: positions, velocities and forces at the library's API.
/// Inside a step the engine works on flat double buffers instead; this type is for setup and read-out.
/// </summary>
public readonly struct Vector3d : IEquatable<Vector3d>
{
    /// <summary>Creates a vector from its three components.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public Vector3d(double x, double y, double z)
    {
        X = x;
        Y = y;
        Z = z;
    }

    /// <summary>The zero vector.</summary>
    public static Vector3d Zero => default;

    /// <summary>The x component.</summary>
    public double X { get; }

    /// <summary>The y component (up, in the course's scenarios).</summary>
    public double Y { get; }

    /// <summary>The z component.</summary>
    public double Z { get; }

    /// <summary>The Euclidean length.</summary>
    public double Length => Math.Sqrt(LengthSquared);

    /// <summary>The squared Euclidean length.</summary>
    public double LengthSquared => (X * X) + (Y * Y) + (Z * Z);

    /// <summary>True when all three components are finite (neither NaN nor infinite).</summary>
    public bool IsFinite => DoubleChecks.IsFinite(X) && DoubleChecks.IsFinite(Y) && DoubleChecks.IsFinite(Z);

    /// <summary>The dot product of two vectors.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static double Dot(Vector3d a, Vector3d b) => (a.X * b.X) + (a.Y * b.Y) + (a.Z * b.Z);

    /// <summary>The cross product a x b.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector3d Cross(Vector3d a, Vector3d b) =>
        new((a.Y * b.Z) - (a.Z * b.Y), (a.Z * b.X) - (a.X * b.Z), (a.X * b.Y) - (a.Y * b.X));

    /// <summary>Component-wise sum.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector3d operator +(Vector3d a, Vector3d b) => new(a.X + b.X, a.Y + b.Y, a.Z + b.Z);

    /// <summary>Component-wise difference.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector3d operator -(Vector3d a, Vector3d b) => new(a.X - b.X, a.Y - b.Y, a.Z - b.Z);

    /// <summary>Negation.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector3d operator -(Vector3d a) => new(-a.X, -a.Y, -a.Z);

    /// <summary>Scaling by a number.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector3d operator *(double s, Vector3d a) => new(s * a.X, s * a.Y, s * a.Z);

    /// <summary>Scaling by a number.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector3d operator *(Vector3d a, double s) => new(s * a.X, s * a.Y, s * a.Z);

    /// <summary>Division by a number.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector3d operator /(Vector3d a, double s) => new(a.X / s, a.Y / s, a.Z / s);

    /// <summary>Exact component-wise equality.</summary>
    public static bool operator ==(Vector3d a, Vector3d b) => a.Equals(b);

    /// <summary>Exact component-wise inequality.</summary>
    public static bool operator !=(Vector3d a, Vector3d b) => !a.Equals(b);

    /// <summary>Converts to the single-precision vector that renderers (Unity meshes, System.Numerics) take.</summary>
    public Vector3 ToVector3() => new((float)X, (float)Y, (float)Z);

    /// <summary>Converts a single-precision vector to double precision (exactly).</summary>
    public static Vector3d FromVector3(Vector3 v) => new(v.X, v.Y, v.Z);

    /// <inheritdoc />
    public bool Equals(Vector3d other) => X.Equals(other.X) && Y.Equals(other.Y) && Z.Equals(other.Z);

    /// <inheritdoc />
    public override bool Equals(object? obj) => obj is Vector3d other && Equals(other);

    /// <inheritdoc />
    public override int GetHashCode() => HashCode.Combine(X, Y, Z);

    /// <summary>Formats as (x, y, z) in the invariant culture, each number in its shortest round-trip form.</summary>
    public override string ToString() => string.Format(
        CultureInfo.InvariantCulture, "({0:R}, {1:R}, {2:R})", X, Y, Z);
}
