namespace ParticlePhysics.Contacts;

/// <summary>
/// What a query of a <see cref="ContactSet"/> met (<see cref="ContactSet.Raycast"/>, <see cref="ContactSet.SphereCast"/>,
/// <see cref="ContactSet.Overlap"/>): an obstacle (its index, and the triangle of a mesh or a height field) or a particle,
/// the point and the normal of the touch, and how far along the query it lies.
/// </summary>
public readonly struct QueryHit
{
    /// <summary>Creates a hit; the queries do this.</summary>
    public QueryHit(int obstacle, int particle, int triangle, Vector3d point, Vector3d normal, double distance)
    {
        Obstacle = obstacle;
        Particle = particle;
        Triangle = triangle;
        Point = point;
        Normal = normal;
        Distance = distance;
    }

    /// <summary>The index of the obstacle hit in <see cref="ContactSet.Obstacles"/>, or -1 for a particle.</summary>
    public int Obstacle { get; }

    /// <summary>The index of the particle hit, or -1 for an obstacle.</summary>
    public int Particle { get; }

    /// <summary>The triangle hit of a <see cref="MeshObstacle"/> or a <see cref="HeightFieldObstacle"/>, else -1.</summary>
    public int Triangle { get; }

    /// <summary>
    /// The point touched, on the surface of what was hit, in metres (for a sphere cast: where the cast sphere touches it;
    /// for an overlap: the surface point nearest the query's centre).
    /// </summary>
    public Vector3d Point { get; }

    /// <summary>The outward unit normal of what was hit at <see cref="Point"/>.</summary>
    public Vector3d Normal { get; }

    /// <summary>How far the ray or the cast sphere's centre moved to the touch, in metres (0 when it starts touching; for an overlap, the query centre's distance to the surface, negative inside).</summary>
    public double Distance { get; }
}
