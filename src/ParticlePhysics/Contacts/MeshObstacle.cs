using System;

namespace ParticlePhysics.Contacts;

/// <summary>
/// A triangle mesh collider: triangles given in the mesh's own frame, placed by a pose (<see cref="Position"/> and
/// three orthonormal axes) that a host may set before each step, and moving with <see cref="Obstacle.Velocity"/>
/// within the step like every obstacle.
/// </summary>
/// <remarks>
/// <para>
/// One-sided (the default): the side a triangle's normal (b - a) x (c - a) points to, counter-clockwise seen from
/// there, is outside, and the distance is signed by the angle-weighted pseudonormal of the nearest feature (face,
/// edge or vertex), exact for a closed, consistently wound mesh: a closed mesh (<see cref="IsClosed"/>) is a solid,
/// and what reaches its inside is pushed out through the nearest face. An open one-sided mesh (a floor, a terrain) is
/// the surface of the solid behind it, however far behind, within the surfaces through its rim perpendicular to its
/// faces (below a terrain, the column under it): a particle beside the rim is outside. It has no bounds, so every
/// particle is tested against it. Two-sided (<see cref="TwoSided"/>): a
/// sheet without inside; the distance is unsigned and keeps a particle on the side it is on.
/// </para>
/// <para>
/// Impacts are found at their time within the step by the contact search's safe steps, the least of the triangles'
/// tangent bounds (<see cref="TriangleMesh.SafeStep"/>), so a particle at 1000 m/s meets a wall 5 cm thick at 60 Hz;
/// resting, restitution and friction are those of every obstacle. A bounding volume hierarchy over the triangles
/// keeps the cost of a query near the log of their count. Turning the mesh (<see cref="SetOrientation"/>) takes
/// effect at once, as for the other obstacles.
/// </para>
/// </remarks>
public sealed class MeshObstacle : Obstacle
{
    private readonly TriangleMesh _mesh;
    private Vector3d _position;
    private Vector3d _axisX = new(1, 0, 0);
    private Vector3d _axisY = new(0, 1, 0);
    private Vector3d _axisZ = new(0, 0, 1);

    /// <summary>Creates a mesh at the origin with the world's axes.</summary>
    /// <param name="vertices">x, y, z of each vertex in the mesh's frame, in metres (finite; copied).</param>
    /// <param name="triangles">Three vertex indices per triangle, counter-clockwise seen from outside (copied); no triangle may have zero area.</param>
    /// <param name="twoSided">True for a sheet with no inside (<see cref="TwoSided"/>).</param>
    /// <param name="restitution">e, 0 to 1 (default 0).</param>
    /// <param name="friction">mu &gt;= 0 (default 0).</param>
    /// <exception cref="ArgumentException">A count, an index, a coordinate or a triangle that is not allowed; the message names it.</exception>
    public MeshObstacle(double[] vertices, int[] triangles, bool twoSided = false, double restitution = 0.0, double friction = 0.0)
        : this(new TriangleMesh(vertices, triangles, nameof(vertices), nameof(triangles)), twoSided, restitution, friction)
    {
    }

    internal MeshObstacle(TriangleMesh mesh, bool twoSided, double restitution, double friction)
        : base(restitution, friction)
    {
        _mesh = mesh;
        TwoSided = twoSided;
    }

    /// <summary>Where the mesh's origin is, in metres (at <see cref="Obstacle.ReferenceTime"/>).</summary>
    public Vector3d Position
    {
        get => _position;
        set
        {
            Guard.Finite(value, nameof(Position));
            _position = value;
        }
    }

    /// <summary>The mesh's x axis in the world (unit length).</summary>
    public Vector3d AxisX => _axisX;

    /// <summary>The mesh's y axis in the world (unit length).</summary>
    public Vector3d AxisY => _axisY;

    /// <summary>The mesh's z axis in the world, AxisX x AxisY.</summary>
    public Vector3d AxisZ => _axisZ;

    /// <summary>False (the default): the back of the surface is solid. True: a sheet with two open sides.</summary>
    public bool TwoSided { get; set; }

    /// <summary>
    /// Whether every edge is shared by two triangles running along it in opposite directions: a closed, consistently
    /// wound surface with an inside.
    /// </summary>
    public bool IsClosed => _mesh.IsClosed;

    /// <summary>The number of triangles.</summary>
    public int TriangleCount => _mesh.Count;

    /// <summary>
    /// Turns the mesh: its x axis along <paramref name="axisX"/>, its y axis along the part of <paramref name="axisY"/>
    /// orthogonal to that, its z axis their cross product (as <see cref="BoxObstacle.SetOrientation"/>).
    /// </summary>
    /// <exception cref="ArgumentOutOfRangeException">An axis is zero or not finite, or the two are parallel.</exception>
    public void SetOrientation(Vector3d axisX, Vector3d axisY)
    {
        // Into locals first: a refused pair leaves the pose as it was.
        UnitVectors.Frame(axisX, axisY, out var x, out var y, out var z);
        _axisX = x;
        _axisY = y;
        _axisZ = z;
    }

    /// <summary>Triangle <paramref name="triangle"/>'s corners where the pose puts them, in metres.</summary>
    /// <exception cref="ArgumentOutOfRangeException">No such triangle.</exception>
    public void GetTriangle(int triangle, out Vector3d a, out Vector3d b, out Vector3d c)
    {
        if (triangle < 0 || triangle >= _mesh.Count)
        {
            throw new ArgumentOutOfRangeException(nameof(triangle), triangle, $"triangle must be from 0 to {_mesh.Count - 1}; got {triangle}.");
        }

        _mesh.Corners(triangle, out a, out b, out c);
        a = ToWorld(a);
        b = ToWorld(b);
        c = ToWorld(c);
    }

    /// <inheritdoc />
    public override void Translate(Vector3d offset) => Position = _position + offset;

    /// <inheritdoc />
    public override double Distance(double x, double y, double z, out double nx, out double ny, out double nz)
    {
        var d = _mesh.Distance(ToLocal(new Vector3d(x, y, z)), !TwoSided, out var gradient, out _);
        var n = Rotate(gradient);
        (nx, ny, nz) = (n.X, n.Y, n.Z);
        return d;
    }

    /// <inheritdoc />
    /// <remarks>An open one-sided mesh has none: the solid behind it reaches to infinity.</remarks>
    public override bool TryGetBounds(out Vector3d min, out Vector3d max)
    {
        if (!TwoSided && !_mesh.IsClosed)
        {
            return base.TryGetBounds(out min, out max);
        }

        SurfaceBounds(out min, out max);
        return true;
    }

    /// <inheritdoc />
    /// <remarks>
    /// Through the hierarchy, nearest box first: a ray's exact crossing of a triangle (Möller and Trumbore), a
    /// sphere's first touch by Newton's steps on the triangle's convex distance. <paramref name="feature"/> receives
    /// the triangle. A start within the radius of the surface, or behind a one-sided one, hits at distance 0.
    /// </remarks>
    public override bool Cast(
        Vector3d origin, Vector3d direction, double radius, double maxDistance, out double distance, out Vector3d normal, out int feature)
    {
        // Whether it starts touching or behind the surface: only a start near the mesh's box can (or any start, behind an
        // open one-sided mesh, whose solid reaches past its box); a far start would walk much of the tree for nothing.
        var local = ToLocal(origin);
        var lo = _mesh.Min;
        var hi = _mesh.Max;
        var outside = Math.Max(Math.Max(Math.Max(lo.X - local.X, local.X - hi.X), Math.Max(lo.Y - local.Y, local.Y - hi.Y)), Math.Max(lo.Z - local.Z, local.Z - hi.Z));
        var mayTouch = !(outside > radius) || (!TwoSided && !_mesh.IsClosed);
        var gap = 1.0;
        var gradient = Vector3d.Zero;
        var nearest = -1;
        if (mayTouch)
        {
            gap = _mesh.Distance(local, !TwoSided, out gradient, out nearest) - radius;
        }

        if (!(gap > 0.0))
        {
            distance = 0.0;
            normal = Rotate(gradient);
            feature = nearest;
            return true;
        }

        var d = new Vector3d(Vector3d.Dot(direction, _axisX), Vector3d.Dot(direction, _axisY), Vector3d.Dot(direction, _axisZ));
        var hit = _mesh.Cast(local, d, radius, maxDistance, out distance, out var n, out feature);
        normal = Rotate(n);
        return hit;
    }

    /// <inheritdoc />
    protected override ObstacleShape Describe(Vector3d offset)
    {
        var half = 0.5 * (_mesh.Max - _mesh.Min);
        return new ObstacleShape(ObstacleKind.Mesh, _position + offset, _axisX, _axisY, _axisZ, half, _mesh.Vertices, _mesh.Triangles);
    }

    /// <inheritdoc />
    /// <remarks>
    /// No triangle within reach: a sheet's unsigned distance is more, and so is a closed mesh's at a point outside its
    /// box (the solid lies inside it); elsewhere only the sign is unknown, and the exact distance decides, and is kept
    /// as the known fact. phi is 1-Lipschitz, so a fact phi(k) &gt;= g gives phi(p) &gt;= g - |p - k| outside, which settles
    /// a particle hanging in the mesh's box without a walk to the nearest triangle in each substep. The pose does not
    /// enter the fact (it is in the mesh's frame) and the triangles never change; a fact is only kept from the signed
    /// distance, which for a point outside is also the two-sided one.
    /// </remarks>
    internal override bool IsFarOutside(double x, double y, double z, double reach, ref Vector3d knownPoint, ref double knownGap)
    {
        var local = ToLocal(new Vector3d(x, y, z));
        if (knownGap - (local - knownPoint).Length > reach)
        {
            return true;
        }

        if (_mesh.AnyWithin(local, reach))
        {
            return false;
        }

        if (TwoSided)
        {
            return true;
        }

        var lo = _mesh.Min;
        var hi = _mesh.Max;
        var outsideBox = local.X < lo.X || local.X > hi.X || local.Y < lo.Y || local.Y > hi.Y || local.Z < lo.Z || local.Z > hi.Z;
        if (_mesh.IsClosed && outsideBox)
        {
            return true;
        }

        var d = _mesh.Distance(local, true, out _, out _);
        if (!(d > reach))
        {
            return false;
        }

        knownPoint = local;
        knownGap = d;
        return true;
    }

    /// <summary>The least of the triangles' tangent bounds (<see cref="TriangleMesh.SafeStep"/>) while the gap is open.</summary>
    internal override double SafeStep(
        double qx, double qy, double qz, double wx, double wy, double wz, double radius, double gap, double rate, double bend, double limit)
    {
        if (!(gap > ContactSearch.Tolerance))
        {
            return ContactSearch.SafeStep(gap, rate, bend);
        }

        var w = new Vector3d(wx, wy, wz);
        var local = new Vector3d(Vector3d.Dot(w, _axisX), Vector3d.Dot(w, _axisY), Vector3d.Dot(w, _axisZ));
        return _mesh.SafeStep(ToLocal(new Vector3d(qx, qy, qz)), local, radius, bend, limit);
    }

    /// <summary>The box around the triangles where the pose puts them, grown by 1e-12 of its size against rounding.</summary>
    private void SurfaceBounds(out Vector3d min, out Vector3d max)
    {
        var centre = ToWorld(0.5 * (_mesh.Min + _mesh.Max));
        var h = 0.5 * (_mesh.Max - _mesh.Min);
        var reach = new Vector3d(
            (Math.Abs(_axisX.X) * h.X) + (Math.Abs(_axisY.X) * h.Y) + (Math.Abs(_axisZ.X) * h.Z),
            (Math.Abs(_axisX.Y) * h.X) + (Math.Abs(_axisY.Y) * h.Y) + (Math.Abs(_axisZ.Y) * h.Z),
            (Math.Abs(_axisX.Z) * h.X) + (Math.Abs(_axisY.Z) * h.Y) + (Math.Abs(_axisZ.Z) * h.Z));
        var margin = 1e-12 * (reach.X + reach.Y + reach.Z + Math.Abs(centre.X) + Math.Abs(centre.Y) + Math.Abs(centre.Z));
        reach += new Vector3d(margin, margin, margin);
        min = centre - reach;
        max = centre + reach;
    }

    private Vector3d ToLocal(Vector3d p)
    {
        var d = p - _position;
        return new Vector3d(Vector3d.Dot(d, _axisX), Vector3d.Dot(d, _axisY), Vector3d.Dot(d, _axisZ));
    }

    private Vector3d Rotate(Vector3d v) => (v.X * _axisX) + (v.Y * _axisY) + (v.Z * _axisZ);

    private Vector3d ToWorld(Vector3d p) => _position + Rotate(p);
}
