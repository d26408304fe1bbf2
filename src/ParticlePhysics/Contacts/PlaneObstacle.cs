namespace ParticlePhysics.Contacts;

/// <summary>
/// A half-space bounded by a plane through <see cref="Point"/> with outward unit normal <see cref="Normal"/>: the ground,
/// a wall. phi(p) = (p - Point) . n; gradient n. Nothing can tunnel through it: it is infinitely thick.
/// </summary>
public sealed class PlaneObstacle : Obstacle
{
    private Vector3d _point;
    private Vector3d _normal = new(0, 1, 0);

    /// <summary>Creates a plane.</summary>
    /// <param name="point">A point on the plane, in metres.</param>
    /// <param name="normal">The outward normal (any non-zero length; it is normalised): particles stay on its side.</param>
    /// <param name="restitution">e, 0 to 1 (default 0).</param>
    /// <param name="friction">mu &gt;= 0 (default 0).</param>
    public PlaneObstacle(Vector3d point, Vector3d normal, double restitution = 0.0, double friction = 0.0)
        : base(restitution, friction)
    {
        Point = point;
        Normal = normal;
    }

    /// <summary>The ground y = 0 (normal +y).</summary>
    public static PlaneObstacle Ground(double restitution = 0.0, double friction = 0.0) =>
        new(Vector3d.Zero, new Vector3d(0, 1, 0), restitution, friction);

    /// <summary>A point on the plane, in metres (at <see cref="Obstacle.ReferenceTime"/>).</summary>
    public Vector3d Point
    {
        get => _point;
        set
        {
            Guard.Finite(value, nameof(Point));
            _point = value;
        }
    }

    /// <summary>The outward unit normal; set any finite non-zero vector, it is normalised.</summary>
    public Vector3d Normal
    {
        get => _normal;
        set => _normal = UnitVectors.Normalized(value, nameof(Normal));
    }

    /// <inheritdoc />
    public override bool IsConvex => true;

    /// <inheritdoc />
    public override void Translate(Vector3d offset) => Point = _point + offset;

    /// <inheritdoc />
    protected override ObstacleShape Describe(Vector3d offset)
    {
        UnitVectors.Tangents(_normal, out var tangent, out var bitangent);
        return new ObstacleShape(ObstacleKind.Plane, _point + offset, tangent, _normal, bitangent, Vector3d.Zero, 0.0);
    }

    /// <inheritdoc />
    /// <remarks>Closed form: the gap g = phi(o) - r falls at d . n per metre, so it is reached at g / -(d . n).</remarks>
    public override bool Cast(
        Vector3d origin, Vector3d direction, double radius, double maxDistance, out double distance, out Vector3d normal, out int feature)
    {
        feature = -1;
        normal = _normal;
        distance = 0.0;
        var gap = Distance(origin.X, origin.Y, origin.Z, out _, out _, out _) - radius;
        if (!(gap > 0.0))
        {
            return true;
        }

        var rate = Vector3d.Dot(direction, _normal);
        distance = gap / -rate;
        return rate < 0.0 && distance <= maxDistance;
    }

    /// <inheritdoc />
    public override double Distance(double x, double y, double z, out double nx, out double ny, out double nz)
    {
        nx = _normal.X;
        ny = _normal.Y;
        nz = _normal.Z;
        return ((x - _point.X) * nx) + ((y - _point.Y) * ny) + ((z - _point.Z) * nz);
    }
}
