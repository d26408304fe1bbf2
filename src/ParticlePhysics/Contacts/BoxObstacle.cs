using System;

namespace ParticlePhysics.Contacts;

/// <summary>
/// A solid oriented box: half extents h along three orthonormal axes u_k around <see cref="Center"/> (a crate, a thin
/// wall). With l_k = (p - c) . u_k and e_k = |l_k| - h_k, the exact signed distance is |max(e, 0)| outside and
/// max_k e_k inside; its gradient is sum_k sign(l_k) max(e_k, 0) u_k / phi outside, sign(l_k) u_k of the nearest face
/// inside.
/// </summary>
public sealed class BoxObstacle : Obstacle
{
    private Vector3d _center;
    private Vector3d _halfExtents;
    private Vector3d _axisX = new(1, 0, 0);
    private Vector3d _axisY = new(0, 1, 0);
    private Vector3d _axisZ = new(0, 0, 1);

    /// <summary>Creates a box aligned with the world axes.</summary>
    /// <param name="center">Its centre, in metres.</param>
    /// <param name="halfExtents">Half its size along x, y and z: positive finite numbers of metres.</param>
    /// <param name="restitution">e, 0 to 1 (default 0).</param>
    /// <param name="friction">mu &gt;= 0 (default 0).</param>
    public BoxObstacle(Vector3d center, Vector3d halfExtents, double restitution = 0.0, double friction = 0.0)
        : base(restitution, friction)
    {
        Center = center;
        HalfExtents = halfExtents;
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

    /// <summary>Half the size along each of the box's axes: positive finite numbers of metres.</summary>
    public Vector3d HalfExtents
    {
        get => _halfExtents;
        set
        {
            Guard.PositiveFinite(value.X, nameof(HalfExtents) + ".X");
            Guard.PositiveFinite(value.Y, nameof(HalfExtents) + ".Y");
            Guard.PositiveFinite(value.Z, nameof(HalfExtents) + ".Z");
            _halfExtents = value;
        }
    }

    /// <summary>The box's first axis (unit length).</summary>
    public Vector3d AxisX => _axisX;

    /// <summary>The box's second axis (unit length).</summary>
    public Vector3d AxisY => _axisY;

    /// <summary>The box's third axis, AxisX x AxisY.</summary>
    public Vector3d AxisZ => _axisZ;

    /// <summary>
    /// Turns the box: its first axis along <paramref name="axisX"/>, its second along the part of
    /// <paramref name="axisY"/> orthogonal to that (Gram-Schmidt), its third their cross product.
    /// </summary>
    /// <remarks>Any finite lengths will do (1e-200 or 1e300): both axes are normalised before they are compared.</remarks>
    /// <exception cref="ArgumentOutOfRangeException">
    /// An axis is zero or not finite, or the two are parallel (the sine of their angle at most 1e-12).
    /// </exception>
    public void SetOrientation(Vector3d axisX, Vector3d axisY)
    {
        // Into locals first: a refused pair leaves the pose as it was.
        UnitVectors.Frame(axisX, axisY, out var x, out var y, out var z);
        _axisX = x;
        _axisY = y;
        _axisZ = z;
    }

    /// <inheritdoc />
    public override bool IsConvex => true;

    /// <inheritdoc />
    public override void Translate(Vector3d offset) => Center = _center + offset;

    /// <inheritdoc />
    protected override ObstacleShape Describe(Vector3d offset) =>
        new(ObstacleKind.Box, _center + offset, _axisX, _axisY, _axisZ, _halfExtents, 0.0);

    /// <inheritdoc />
    public override bool TryGetBounds(out Vector3d min, out Vector3d max)
    {
        // The box's reach along each world axis: the half extents projected, |u_k . e_c| h_k summed over its axes.
        var h = _halfExtents;
        var reach = new Vector3d(
            (Math.Abs(_axisX.X) * h.X) + (Math.Abs(_axisY.X) * h.Y) + (Math.Abs(_axisZ.X) * h.Z),
            (Math.Abs(_axisX.Y) * h.X) + (Math.Abs(_axisY.Y) * h.Y) + (Math.Abs(_axisZ.Y) * h.Z),
            (Math.Abs(_axisX.Z) * h.X) + (Math.Abs(_axisY.Z) * h.Y) + (Math.Abs(_axisZ.Z) * h.Z));
        min = _center - reach;
        max = _center + reach;
        return true;
    }

    /// <inheritdoc />
    public override double Distance(double x, double y, double z, out double nx, out double ny, out double nz)
    {
        double dx = x - _center.X, dy = y - _center.Y, dz = z - _center.Z;
        var l0 = (dx * _axisX.X) + (dy * _axisX.Y) + (dz * _axisX.Z);
        var l1 = (dx * _axisY.X) + (dy * _axisY.Y) + (dz * _axisY.Z);
        var l2 = (dx * _axisZ.X) + (dy * _axisZ.Y) + (dz * _axisZ.Z);
        var e0 = Math.Abs(l0) - _halfExtents.X;
        var e1 = Math.Abs(l1) - _halfExtents.Y;
        var e2 = Math.Abs(l2) - _halfExtents.Z;
        var s0 = l0 < 0.0 ? -1.0 : 1.0;
        var s1 = l1 < 0.0 ? -1.0 : 1.0;
        var s2 = l2 < 0.0 ? -1.0 : 1.0;
        if (e0 > 0.0 || e1 > 0.0 || e2 > 0.0)
        {
            // Outside: the distance to the nearest point of the box, through the positive excesses only.
            var o0 = Math.Max(e0, 0.0) * s0;
            var o1 = Math.Max(e1, 0.0) * s1;
            var o2 = Math.Max(e2, 0.0) * s2;
            var length = Math.Sqrt((o0 * o0) + (o1 * o1) + (o2 * o2));
            nx = ((o0 * _axisX.X) + (o1 * _axisY.X) + (o2 * _axisZ.X)) / length;
            ny = ((o0 * _axisX.Y) + (o1 * _axisY.Y) + (o2 * _axisZ.Y)) / length;
            nz = ((o0 * _axisX.Z) + (o1 * _axisY.Z) + (o2 * _axisZ.Z)) / length;
            return length;
        }

        // Inside (or on the surface): the nearest face, the largest (least negative) excess.
        if (e0 >= e1 && e0 >= e2)
        {
            nx = s0 * _axisX.X;
            ny = s0 * _axisX.Y;
            nz = s0 * _axisX.Z;
            return e0;
        }

        if (e1 >= e2)
        {
            nx = s1 * _axisY.X;
            ny = s1 * _axisY.Y;
            nz = s1 * _axisY.Z;
            return e1;
        }

        nx = s2 * _axisZ.X;
        ny = s2 * _axisZ.Y;
        nz = s2 * _axisZ.Z;
        return e2;
    }
}
