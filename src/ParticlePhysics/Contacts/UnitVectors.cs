using System;

namespace ParticlePhysics.Contacts;

/// <summary>Unit vectors for the obstacles' parameters.</summary>
internal static class UnitVectors
{
    /// <summary><paramref name="value"/> / |value| (also when |value| overflows or underflows); throws for a zero or non-finite vector.</summary>
    public static Vector3d Normalized(Vector3d value, string name) => Guard.Direction(value, name);

    /// <summary>Two unit vectors that make (t, n, b) a right-handed orthonormal frame with unit <paramref name="n"/>.</summary>
    public static void Tangents(Vector3d n, out Vector3d t, out Vector3d b)
    {
        // The world axis least aligned with n, made orthogonal to it (never degenerate).
        var axis = Math.Abs(n.X) <= Math.Abs(n.Y) && Math.Abs(n.X) <= Math.Abs(n.Z) ? new Vector3d(1, 0, 0)
            : Math.Abs(n.Y) <= Math.Abs(n.Z) ? new Vector3d(0, 1, 0) : new Vector3d(0, 0, 1);
        t = Normalized(Vector3d.Cross(axis, n), nameof(n));
        b = Vector3d.Cross(t, n);
    }

    /// <summary>
    /// The right-handed orthonormal frame of a pose: x along <paramref name="axisX"/>, y along the part of
    /// <paramref name="axisY"/> orthogonal to it (Gram-Schmidt), z = x cross y. Throws for a zero or non-finite axis, or
    /// axes whose angle has a sine of at most 1e-12.
    /// </summary>
    public static void Frame(Vector3d axisX, Vector3d axisY, out Vector3d x, out Vector3d y, out Vector3d z)
    {
        // Normalised first: |axisY| itself underflows to 0 below about 1e-154 and overflows above about 1e154, and a
        // test scaled by it would call such axes parallel. For unit u, |u - (u . x) x| is the sine of the angle.
        x = Normalized(axisX, nameof(axisX));
        var u = Normalized(axisY, nameof(axisY));
        y = u - (Vector3d.Dot(u, x) * x);
        if (!(y.Length > 1e-12))
        {
            throw new ArgumentOutOfRangeException(
                nameof(axisY), axisY, $"axisY must not be parallel to axisX {axisX}; got {axisY}.");
        }

        y = Normalized(y, nameof(axisY));
        z = Vector3d.Cross(x, y);
    }
}
