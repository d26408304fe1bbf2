using System.Runtime.CompilerServices;

namespace ParticlePhysics.Contacts;

/// <summary>
/// A solid ball of radius R around <see cref="Center"/>. phi(p) = |p - c| - R; gradient (p - c) / |p - c| (at the
/// centre itself, +y).
/// </summary>
public sealed class SphereObstacle : Obstacle
{
    private Vector3d _center;
    private double _radius;

    /// <summary>Creates a sphere.</summary>
    /// <param name="center">Its centre, in metres.</param>
    /// <param name="radius">Its radius, a positive finite number of metres.</param>
    /// <param name="restitution">e, 0 to 1 (default 0).</param>
    /// <param name="friction">mu &gt;= 0 (default 0).</param>
    public SphereObstacle(Vector3d center, double radius, double restitution = 0.0, double friction = 0.0)
        : base(restitution, friction)
    {
        Center = center;
        Radius = radius;
    }

    /// <summary>The centre, in metres (at <see cref="Obstacle.ReferenceTime"/>).</summary>
    public Vector3d Center
    {
        get => _center;
        set
        {
            Guard.Finite(value, nameof(Center));
            _center = value;
        }
    }

    /// <summary>The radius, a positive finite number of metres.</summary>
    public double Radius
    {
        get => _radius;
        set
        {
            Guard.PositiveFinite(value, nameof(Radius));
            _radius = value;
        }
    }

    /// <inheritdoc />
    public override bool IsConvex => true;

    /// <inheritdoc />
    public override void Translate(Vector3d offset) => Center = _center + offset;

    /// <inheritdoc />
    protected override ObstacleShape Describe(Vector3d offset) => new(
        ObstacleKind.Sphere, _center + offset, new Vector3d(1, 0, 0), new Vector3d(0, 1, 0), new Vector3d(0, 0, 1),
        Vector3d.Zero, _radius);

    /// <inheritdoc />
    public override bool TryGetBounds(out Vector3d min, out Vector3d max)
    {
        var reach = new Vector3d(_radius, _radius, _radius);
        min = _center - reach;
        max = _center + reach;
        return true;
    }

    /// <inheritdoc />
    /// <remarks>Closed form: the smaller root of |o + t d - c| = R + r.</remarks>
    public override bool Cast(
        Vector3d origin, Vector3d direction, double radius, double maxDistance, out double distance, out Vector3d normal, out int feature)
    {
        feature = -1;
        return ShapeCasts.Ball(_center, _radius, origin, direction, radius, maxDistance, out distance, out normal);
    }

    /// <inheritdoc />
    public override double Distance(double x, double y, double z, out double nx, out double ny, out double nz) =>
        PointDistance(x - _center.X, y - _center.Y, z - _center.Z, out nx, out ny, out nz) - _radius;

    /// <summary>|d| and d / |d| (+y when d = 0).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    internal static double PointDistance(double dx, double dy, double dz, out double nx, out double ny, out double nz)
    {
        var length = System.Math.Sqrt((dx * dx) + (dy * dy) + (dz * dz));
        if (length > 0.0)
        {
            nx = dx / length;
            ny = dy / length;
            nz = dz / length;
        }
        else
        {
            nx = 0.0;
            ny = 1.0;
            nz = 0.0;
        }

        return length;
    }
}
