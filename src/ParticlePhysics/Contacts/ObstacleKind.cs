namespace ParticlePhysics.Contacts;

/// <summary>The kinds of <see cref="Obstacle"/>, for renderers and tools that draw them (<see cref="ObstacleShape"/>).</summary>
public enum ObstacleKind
{
    /// <summary>A half-space: everything below a plane through <see cref="ObstacleShape.Center"/> with normal <see cref="ObstacleShape.AxisY"/>.</summary>
    Plane,

    /// <summary>A ball of <see cref="ObstacleShape.Radius"/> around <see cref="ObstacleShape.Center"/>.</summary>
    Sphere,

    /// <summary>
    /// The points within <see cref="ObstacleShape.Radius"/> of a segment along <see cref="ObstacleShape.AxisY"/>, from
    /// Center - HalfExtents.Y AxisY to Center + HalfExtents.Y AxisY.
    /// </summary>
    Capsule,

    /// <summary>An oriented box: <see cref="ObstacleShape.HalfExtents"/> along the three axes around the centre.</summary>
    Box,

    /// <summary>
    /// A triangle mesh: <see cref="ObstacleShape.Vertices"/> and <see cref="ObstacleShape.Triangles"/> in the mesh's own
    /// frame, placed by the centre and the axes.
    /// </summary>
    Mesh,

    /// <summary>
    /// A height field: its grid as <see cref="ObstacleShape.Vertices"/> and two <see cref="ObstacleShape.Triangles"/> per
    /// cell (the surface itself), in the field's frame, whose origin is the centre (world axes).
    /// </summary>
    HeightField,

    /// <summary>A shape of a user's own: a renderer knows only its bounds, <see cref="ObstacleShape.HalfExtents"/> around the centre (zero when unbounded).</summary>
    Custom,
}
