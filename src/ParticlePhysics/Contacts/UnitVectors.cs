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
}
