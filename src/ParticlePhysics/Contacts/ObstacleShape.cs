using System;

namespace ParticlePhysics.Contacts;

/// <summary>
/// What a renderer needs to draw an <see cref="Obstacle"/> at one time: its kind, a centre, three orthonormal axes
/// (a rotation), half extents and a radius. A unit primitive (plane, sphere, capsule, cube) scaled, rotated and moved
/// by these is the obstacle.
/// </summary>
/// <remarks>
/// Plane: a point on it (<see cref="Center"/>), its outward normal (<see cref="AxisY"/>) and two tangents; half extents
/// and radius 0 (it is unbounded). Sphere: centre and radius, the world axes. Capsule: the middle of its segment, the
/// segment's direction as <see cref="AxisY"/>, half its length as <c>HalfExtents.Y</c>, its radius. Box: centre,
/// axes and half extents, radius 0. Mesh and height field: <see cref="Vertices"/> (x, y, z each, in the shape's frame)
/// and <see cref="Triangles"/> (three vertex indices each); a vertex v is at Center + v.x AxisX + v.y AxisY + v.z AxisZ;
/// half extents are those of the vertices' box in that frame. The arrays are the obstacle's own, shared, not copied:
/// read them, do not keep them past a change of the obstacle.
/// </remarks>
public readonly struct ObstacleShape
{
    /// <summary>Creates a description; the obstacles do this.</summary>
    public ObstacleShape(
        ObstacleKind kind, Vector3d center, Vector3d axisX, Vector3d axisY, Vector3d axisZ, Vector3d halfExtents, double radius)
    {
        Kind = kind;
        Center = center;
        AxisX = axisX;
        AxisY = axisY;
        AxisZ = axisZ;
        HalfExtents = halfExtents;
        Radius = radius;
        Vertices = ReadOnlyMemory<double>.Empty;
        Triangles = ReadOnlyMemory<int>.Empty;
    }

    /// <summary>Creates the description of a triangle surface (a mesh or a height field); the obstacles do this.</summary>
    public ObstacleShape(
        ObstacleKind kind, Vector3d center, Vector3d axisX, Vector3d axisY, Vector3d axisZ, Vector3d halfExtents,
        ReadOnlyMemory<double> vertices, ReadOnlyMemory<int> triangles)
        : this(kind, center, axisX, axisY, axisZ, halfExtents, 0.0)
    {
        Vertices = vertices;
        Triangles = triangles;
    }

    /// <summary>The kind of shape.</summary>
    public ObstacleKind Kind { get; }

    /// <summary>The centre (for a plane: a point on it), in metres.</summary>
    public Vector3d Center { get; }

    /// <summary>The shape's first axis (unit length).</summary>
    public Vector3d AxisX { get; }

    /// <summary>The shape's second axis (unit length): a plane's normal, a capsule's segment direction.</summary>
    public Vector3d AxisY { get; }

    /// <summary>The shape's third axis (unit length), AxisX x AxisY.</summary>
    public Vector3d AxisZ { get; }

    /// <summary>Half the size along each axis, in metres (a capsule's half segment length in Y; 0 for a plane and a sphere).</summary>
    public Vector3d HalfExtents { get; }

    /// <summary>The radius of a sphere or a capsule, in metres (0 for a plane and a box).</summary>
    public double Radius { get; }

    /// <summary>A mesh's or a height field's vertices, x, y, z each in the shape's frame (empty for the other kinds).</summary>
    public ReadOnlyMemory<double> Vertices { get; }

    /// <summary>A mesh's or a height field's triangles, three indices into <see cref="Vertices"/> each (empty for the other kinds).</summary>
    public ReadOnlyMemory<int> Triangles { get; }
}
