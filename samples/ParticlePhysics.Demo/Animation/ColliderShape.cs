using System;

namespace ParticlePhysics.Demo.Animation;

/// <summary>The kinds of fixed shape a replay draws.</summary>
internal enum ColliderKind
{
    /// <summary>An infinite plane: <see cref="ColliderShape.Center"/> is a point on it, <see cref="ColliderShape.Normal"/> its outward normal.</summary>
    Plane,

    /// <summary>A ball: <see cref="ColliderShape.Center"/> and <see cref="ColliderShape.Radius"/>.</summary>
    Sphere,

    /// <summary>
    /// A segment grown by <see cref="ColliderShape.Radius"/>: the segment runs along the local y axis
    /// (<see cref="ColliderShape.AxisY"/>) from Center - h AxisY to Center + h AxisY, h = HalfExtents.Y.
    /// </summary>
    Capsule,

    /// <summary>An oriented box: Center, HalfExtents along the local axes AxisX, AxisY, AxisZ.</summary>
    Box,
}

/// <summary>
/// A collider as plain data, for drawing only: its kind, centre, radius, normal, half-extents and orientation (the
/// local axes in world coordinates, the columns of its rotation matrix). Fields a kind does not use are zero.
/// Build one with the factories, which take each shape the way a physics engine describes it.
/// </summary>
internal sealed record ColliderShape(
    ColliderKind Kind,
    Vector3d Center,
    double Radius,
    Vector3d Normal,
    Vector3d HalfExtents,
    Vector3d AxisX,
    Vector3d AxisY,
    Vector3d AxisZ)
{
    private static readonly Vector3d _unitX = new(1, 0, 0);
    private static readonly Vector3d _unitY = new(0, 1, 0);
    private static readonly Vector3d _unitZ = new(0, 0, 1);

    /// <summary>The plane through <paramref name="point"/> with outward normal <paramref name="normal"/> (normalised here).</summary>
    public static ColliderShape Plane(Vector3d point, Vector3d normal)
    {
        var n = Unit(normal, nameof(normal));
        return new ColliderShape(ColliderKind.Plane, point, 0, n, Vector3d.Zero, _unitX, _unitY, _unitZ);
    }

    /// <summary>A sphere of <paramref name="radius"/> about <paramref name="center"/>.</summary>
    public static ColliderShape Sphere(Vector3d center, double radius) =>
        new(ColliderKind.Sphere, center, radius, Vector3d.Zero, new Vector3d(radius, radius, radius), _unitX, _unitY, _unitZ);

    /// <summary>The capsule around the segment from <paramref name="start"/> to <paramref name="end"/>, grown by <paramref name="radius"/>.</summary>
    public static ColliderShape Capsule(Vector3d start, Vector3d end, double radius)
    {
        var axis = end - start;
        var length = axis.Length;
        var y = length > 0 ? axis / length : _unitY;
        var (x, z) = Perpendiculars(y);
        return new ColliderShape(ColliderKind.Capsule, 0.5 * (start + end), radius, Vector3d.Zero, new Vector3d(radius, 0.5 * length, radius), x, y, z);
    }

    /// <summary>A box of <paramref name="halfExtents"/> along its local axes (three orthonormal vectors in world coordinates).</summary>
    public static ColliderShape Box(Vector3d center, Vector3d halfExtents, Vector3d axisX, Vector3d axisY, Vector3d axisZ) =>
        new(ColliderKind.Box, center, 0, Vector3d.Zero, halfExtents, Unit(axisX, nameof(axisX)), Unit(axisY, nameof(axisY)), Unit(axisZ, nameof(axisZ)));

    /// <summary>A box turned by the unit quaternion (w, x, y, z) from the world axes.</summary>
    public static ColliderShape Box(Vector3d center, Vector3d halfExtents, double w, double x, double y, double z)
    {
        // The columns of the rotation matrix of q = (w, x, y, z).
        var axisX = new Vector3d(1 - (2 * ((y * y) + (z * z))), 2 * ((x * y) + (w * z)), 2 * ((x * z) - (w * y)));
        var axisY = new Vector3d(2 * ((x * y) - (w * z)), 1 - (2 * ((x * x) + (z * z))), 2 * ((y * z) + (w * x)));
        var axisZ = new Vector3d(2 * ((x * z) + (w * y)), 2 * ((y * z) - (w * x)), 1 - (2 * ((x * x) + (y * y))));
        return Box(center, halfExtents, axisX, axisY, axisZ);
    }

    private static Vector3d Unit(Vector3d v, string name)
    {
        var length = v.Length;
        if (!(length > 0) || !double.IsFinite(length))
        {
            throw new ArgumentException($"{name} must be a finite non-zero vector; got {v}.", name);
        }

        return v / length;
    }

    private static (Vector3d X, Vector3d Z) Perpendiculars(Vector3d y)
    {
        var helper = Math.Abs(y.X) < 0.9 ? _unitX : _unitZ;
        var z = Vector3d.Cross(helper, y);
        z /= z.Length;
        return (Vector3d.Cross(y, z), z);
    }
}
