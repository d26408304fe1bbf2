using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Contacts;

/// <summary>
/// The points within radius R of the segment from <see cref="Start"/> to <see cref="End"/> (a limb, a bar).
/// phi(p) = |p - c(p)| - R with c(p) = a + clamp(((p - a) . (b - a)) / |b - a|^2, 0, 1) (b - a), the closest point of
/// the segment; gradient (p - c) / |p - c|. A segment of length 0 is a sphere.
/// </summary>
public sealed class CapsuleObstacle : Obstacle
{
    private Vector3d _start;
    private Vector3d _end;
    private double _radius;

    /// <summary>Creates a capsule.</summary>
    /// <param name="start">One end of its segment, in metres.</param>
    /// <param name="end">The other end.</param>
    /// <param name="radius">Its radius, a positive finite number of metres.</param>
    /// <param name="restitution">e, 0 to 1 (default 0).</param>
    /// <param name="friction">mu &gt;= 0 (default 0).</param>
    public CapsuleObstacle(Vector3d start, Vector3d end, double radius, double restitution = 0.0, double friction = 0.0)
        : base(restitution, friction)
    {
        Guard.Finite(start, nameof(Start));
        Guard.Finite(end, nameof(End));
        CheckSegment(start, end, nameof(End));
        _start = start;
        _end = end;
        Radius = radius;
    }

    /// <summary>One end of the segment, in metres (at <see cref="Obstacle.ReferenceTime"/>).</summary>
    public Vector3d Start
    {
        get => _start;
        set
        {
            Guard.Finite(value, nameof(Start));
            CheckSegment(value, _end, nameof(Start));
            _start = value;
        }
    }

    /// <summary>The other end of the segment, in metres.</summary>
    public Vector3d End
    {
        get => _end;
        set
        {
            Guard.Finite(value, nameof(End));
            CheckSegment(_start, value, nameof(End));
            _end = value;
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
    public override void Translate(Vector3d offset)
    {
        var start = _start + offset;
        var end = _end + offset;
        Guard.Finite(start, nameof(offset));
        Guard.Finite(end, nameof(offset));
        CheckSegment(start, end, nameof(offset));
        _start = start;
        _end = end;
    }

    /// <summary>The segment's squared length is what the distance divides by: it must be finite (ends less than about 1e154 m apart).</summary>
    private static void CheckSegment(Vector3d start, Vector3d end, string name)
    {
        var axis = end - start;
        if (!DoubleChecks.IsFinite(axis.LengthSquared))
        {
            throw new ArgumentOutOfRangeException(
                name,
                name == nameof(Start) ? start : end,
                $"The capsule's segment from {start} to {end} is too long: its squared length must be finite (ends less "
                + "than about 1e154 m apart).");
        }
    }

    /// <inheritdoc />
    protected override ObstacleShape Describe(Vector3d offset)
    {
        var axis = _end - _start;
        var length = axis.Length;
        var up = length > 0.0 ? axis / length : new Vector3d(0, 1, 0);
        UnitVectors.Tangents(up, out var tangent, out var bitangent);
        return new ObstacleShape(
            ObstacleKind.Capsule, (0.5 * (_start + _end)) + offset, tangent, up, bitangent,
            new Vector3d(0, 0.5 * length, 0), _radius);
    }

    /// <inheritdoc />
    public override bool TryGetBounds(out Vector3d min, out Vector3d max)
    {
        var reach = new Vector3d(_radius, _radius, _radius);
        min = new Vector3d(Math.Min(_start.X, _end.X), Math.Min(_start.Y, _end.Y), Math.Min(_start.Z, _end.Z)) - reach;
        max = new Vector3d(Math.Max(_start.X, _end.X), Math.Max(_start.Y, _end.Y), Math.Max(_start.Z, _end.Z)) + reach;
        return true;
    }

    /// <inheritdoc />
    public override double Distance(double x, double y, double z, out double nx, out double ny, out double nz)
    {
        double ax = _end.X - _start.X, ay = _end.Y - _start.Y, az = _end.Z - _start.Z;
        double px = x - _start.X, py = y - _start.Y, pz = z - _start.Z;
        var lengthSquared = (ax * ax) + (ay * ay) + (az * az);
        var t = lengthSquared > 0.0 ? Math.Min(1.0, Math.Max(0.0, ((px * ax) + (py * ay) + (pz * az)) / lengthSquared)) : 0.0;
        return SphereObstacle.PointDistance(px - (t * ax), py - (t * ay), pz - (t * az), out nx, out ny, out nz) - _radius;
    }
}
