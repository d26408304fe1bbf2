using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Contacts;

/// <summary>
/// A thin cloth's collisions with itself: every particle is kept at least <see cref="Thickness"/> from every triangle
/// of the cloth that is not its neighbour in the rest shape, on the side it came from, so that a folding cloth lies
/// on itself instead of passing through itself between its particles.
/// </summary>
/// <remarks>
/// <para>
/// The scheme: particle-triangle proximity with sidedness (Bridson, Fedkiw and Anderson 2002, "Robust treatment of
/// collisions, contact and friction for cloth animation", as a projection). With q = b0 x0 + b1 x1 + b2 x2 the point of
/// the triangle closest to the particle p at the end of the substep (b its barycentric weights) and u a unit direction,
/// the constraint is C = u . (p - q) - h &gt;= 0 (h the thickness): when q is inside the face, u = sigma n with n the
/// triangle's unit normal and sigma the side p was on at the substep's start, so a particle that crossed the face in
/// the substep is put back on its own side; when q is on an edge or a corner, u = (p - q) / |p - q|. Its gradients
/// are u for p and -b_k u for corner k, so zero-compliance xpbd moves p by w_p dl u and corner k by -w_k b_k dl u with
/// dl = -C / (w_p + sum b_k^2 w_k): momentum is kept, and a pinned particle (w = 0) is not moved.
/// </para>
/// <para>
/// Edges are kept h apart too (ClothSelfCollision.Edges.cs): in a crease sharper than the thickness two triangles can
/// cross with every particle farther than h from the other's face.
/// </para>
/// <para>
/// Neighbours in the rest shape are filtered out, as FleX does: a particle never collides with a triangle it is a
/// corner of or one that was closer than h to it at rest (they would push apart what the membrane holds together).
/// The next ring is not filtered: a crease at that scale is where triangles would cross. Candidates come from a
/// <see cref="BoxGrid"/> of the triangles' boxes over the substep grown by h, each particle's box over the substep the
/// query, so nothing that crossed a face is missed. The particles are projected once per substep in index order, each
/// against its triangles in the grid's order: the same bits on every runtime. Under a force-based integrator
/// (<see cref="Resolve"/>) the same projections sweep the step's end, and each moved particle's velocity changes by
/// its move over the step, as xpbd's would.
/// </para>
/// </remarks>
public sealed partial class ClothSelfCollision : IStatefulConstraintSet
{
    private const int ResolvePasses = 16;

    private readonly int[] _triangles;
    private readonly int[] _particles;        // the set's particles, sorted, each once
    private readonly double[] _rest;          // their rest positions, 3 per world particle index (only theirs used)
    private readonly int[] _edges;            // the unique edges, two particles each, the smaller first
    private readonly double _thickness;
    private readonly double _cellFloor;       // the mean rest edge: smaller cells only add cells to visit

    private readonly BoxGrid _grid = new();
    private double[] _before = Array.Empty<double>();
    private int _contacts;
    private int _contactsBefore; // what LastContactCount showed before the step, for a failed step to restore

    /// <summary>
    /// Self-collision for the triangles <paramref name="triangles"/> (three particle indices of <paramref name="world"/>
    /// each) at <paramref name="thickness"/> metres, the particles' current positions being the rest shape.
    /// </summary>
    public ClothSelfCollision(ParticleWorld world, ReadOnlySpan<int> triangles, double thickness)
    {
        Guard.NotNull(world, nameof(world));
        Guard.PositiveFinite(thickness, nameof(thickness), "(metres)");
        if (triangles.Length == 0 || triangles.Length % 3 != 0)
        {
            throw new ArgumentException($"triangles needs three particle indices per triangle and at least one triangle; got {triangles.Length} indices.", nameof(triangles));
        }

        var list = triangles.ToArray(); // an array: a ReadOnlySpan's indexer does not bind on Mono
        var count = world.Count;
        var used = new bool[count];
        for (var k = 0; k < list.Length; k++)
        {
            Guard.ParticleIndex(list[k], count, $"triangles[{k}]");
            used[list[k]] = true;
        }

        for (var t = 0; t < list.Length; t += 3)
        {
            int a = list[t], b = list[t + 1], c = list[t + 2];
            if (a == b || b == c || a == c)
            {
                throw new ArgumentException($"triangle {t / 3} names particle {(a == b || a == c ? a : b)} twice; a triangle needs three distinct particles.", nameof(triangles));
            }
        }

        _triangles = list;
        _thickness = thickness;
        _rest = new double[3 * count];
        var listed = 0;
        for (var i = 0; i < count; i++)
        {
            if (used[i])
            {
                listed++;
                var position = world.GetPosition(i);
                _rest[3 * i] = position.X;
                _rest[(3 * i) + 1] = position.Y;
                _rest[(3 * i) + 2] = position.Z;
            }
        }

        _particles = new int[listed];
        listed = 0;
        for (var i = 0; i < count; i++)
        {
            if (used[i])
            {
                _particles[listed++] = i;
            }
        }

        _edges = Edges(_triangles, count);
        var lengths = 0.0;
        for (var e = 0; e < _edges.Length; e += 2)
        {
            lengths += (Rest(_edges[e]) - Rest(_edges[e + 1])).Length;
        }

        _cellFloor = 2.0 * lengths / _edges.Length;
    }

    /// <summary>The thickness h, metres: no particle comes closer than this to a triangle that is not its neighbour.</summary>
    public double Thickness => _thickness;

    /// <summary>The number of triangles.</summary>
    public int TriangleCount => _triangles.Length / 3;

    /// <summary>
    /// How many particle-triangle and edge-edge constraints the last call projected (those that were violated); a failed
    /// step puts back what it showed before.
    /// </summary>
    public int LastContactCount => _contacts;

    /// <summary>
    /// Whether particle <paramref name="particle"/> and triangle <paramref name="triangle"/> are neighbours in the rest
    /// shape, which never collide: a corner, or one closer than the thickness at rest.
    /// </summary>
    public bool AreRestNeighbours(int particle, int triangle)
    {
        if ((uint)triangle >= (uint)TriangleCount)
        {
            throw new ArgumentOutOfRangeException(nameof(triangle), triangle, $"triangle must name one of the {TriangleCount} triangles; got {triangle}.");
        }

        Guard.ParticleIndex(particle, _rest.Length / 3, nameof(particle));
        return Filtered(particle, 3 * triangle);
    }

    /// <inheritdoc />
    public void BeginStep() => _contactsBefore = _contacts;

    /// <inheritdoc />
    public void CommitStep()
    {
    }

    /// <inheritdoc />
    public void DiscardStep() => _contacts = _contactsBefore;

    /// <inheritdoc />
    public void Resolve(in ConstraintContext context)
    {
        var x = context.Positions;
        if (_before.Length < x.Length)
        {
            _before = new double[x.Length];
        }

        x.CopyTo(_before);

        // A whole step moves the cloth much farther than a substep does: sweep until nothing is violated, at most
        // ResolvePasses times, so that the step's end is as clean as xpbd's after its substeps.
        var projected = 0;
        for (var pass = 0; pass < ResolvePasses; pass++)
        {
            Project(in context);
            projected += _contacts;
            if (_contacts == 0)
            {
                break;
            }
        }

        _contacts = projected;
        var v = context.Velocities;
        var dt = context.Dt;
        for (var k = 0; k < 3 * context.Count; k++)
        {
            v[k] += (x[k] - _before[k]) / dt;
        }
    }

    /// <inheritdoc />
    public void Project(in ConstraintContext context)
    {
        var x = context.Positions;
        var start = context.StartPositions.ForReading();
        var w = context.InverseMasses.ForReading();
        _contacts = 0;

        // The largest move in the substep: a particle that crossed a face is at most this far past it.
        var move = 0.0;
        foreach (var i in _particles)
        {
            var d = (Read(x, i) - Read(start, i)).Length;
            move = d > move ? d : move;
        }

        var reach = _thickness + move;
        var cell = Math.Max(_cellFloor, 2.0 * _thickness);

        // Particle against triangle: the triangles' boxes over the substep grown by h in the grid, each particle's
        // box over the substep the query.
        var triangles = _triangles.Length / 3;
        _grid.Begin(triangles, cell);
        for (var t = 0; t < triangles; t++)
        {
            int a = _triangles[3 * t], b = _triangles[(3 * t) + 1], c = _triangles[(3 * t) + 2];
            Vector3d low = Read(x, a), high = low;
            Grow(ref low, ref high, Read(x, b));
            Grow(ref low, ref high, Read(x, c));
            Grow(ref low, ref high, Read(start, a));
            Grow(ref low, ref high, Read(start, b));
            Grow(ref low, ref high, Read(start, c));
            _grid.Set(t, low - new Vector3d(_thickness, _thickness, _thickness), high + new Vector3d(_thickness, _thickness, _thickness));
        }

        _grid.End();
        foreach (var p in _particles)
        {
            Vector3d low = Read(x, p), high = low;
            Grow(ref low, ref high, Read(start, p));
            foreach (var t in _grid.Overlapping(low, high))
            {
                var o = 3 * t;
                if (_triangles[o] != p && _triangles[o + 1] != p && _triangles[o + 2] != p && ProjectPair(x, start, w, p, o, reach))
                {
                    _contacts++;
                }
            }
        }

        ProjectEdges(x, start, w, reach, cell);
    }

    /// <inheritdoc />
    /// <remarks>Nothing: the velocities xpbd takes from the projected positions already separate the pair.</remarks>
    public void SolveVelocities(in ConstraintContext context)
    {
    }

    private bool ProjectPair(Span<double> x, Span<double> start, Span<double> w, int p, int t, double reach)
    {
        int a = _triangles[t], b = _triangles[t + 1], c = _triangles[t + 2];
        Vector3d xa = Read(x, a), xb = Read(x, b), xc = Read(x, c), xp = Read(x, p);
        var normal = Vector3d.Cross(xb - xa, xc - xa);
        var twiceArea = normal.Length;
        if (!(twiceArea > 0.0))
        {
            return false;
        }

        normal /= twiceArea;

        // Cheap rejection: at least h from the face's plane, on the side it started on (the start triangle's plane
        // offset is that of every point of it), it can be neither within h nor across.
        var planeOffset = Vector3d.Dot(xp - xa, normal);
        if (planeOffset >= _thickness || planeOffset <= -_thickness)
        {
            var sa0 = Read(start, a);
            var startSide = Vector3d.Dot(Read(start, p) - sa0, Vector3d.Cross(Read(start, b) - sa0, Read(start, c) - sa0));
            if ((startSide > 0.0) == (planeOffset > 0.0) && startSide != 0.0)
            {
                return false;
            }
        }

        var squared = TriangleGeometry.Closest(xp, xa, xb, xc, out var closest, out var feature);
        Vector3d u;
        double gap;
        Barycentric(closest, xa, xb, xc, out var ba, out var bb, out var bc);
        if (feature == TriangleGeometry.Face)
        {
            // The side it came from: the start's particle against the start's triangle at the same weights.
            Vector3d sa = Read(start, a), sb = Read(start, b), sc = Read(start, c);
            var startNormal = Vector3d.Cross(sb - sa, sc - sa);
            var startLength = startNormal.Length;
            if (!(startLength > 0.0))
            {
                return false;
            }

            var startOffset = Vector3d.Dot(Read(start, p) - ((ba * sa) + (bb * sb) + (bc * sc)), startNormal) / startLength;
            if (Math.Abs(startOffset) > reach)
            {
                return false; // far from the face's plane at the start: not a crossing this substep
            }

            var offset = Vector3d.Dot(xp - closest, normal);
            var side = startOffset > 0.0 || (startOffset == 0.0 && offset >= 0.0) ? 1.0 : -1.0;
            u = side * normal;
            gap = (side * offset) - _thickness;
        }
        else
        {
            if (!(squared < _thickness * _thickness) || !(squared > 0.0))
            {
                return false;
            }

            var distance = Math.Sqrt(squared);
            u = (xp - closest) / distance;
            gap = distance - _thickness;
        }

        if (!(gap < 0.0) || Filtered(p, t))
        {
            return false;
        }

        var weights = w[p] + (ba * ba * w[a]) + (bb * bb * w[b]) + (bc * bc * w[c]);
        if (!(weights > 0.0))
        {
            return false;
        }

        var dl = -gap / weights;
        Add(x, p, (w[p] * dl) * u);
        Add(x, a, (-w[a] * ba * dl) * u);
        Add(x, b, (-w[b] * bb * dl) * u);
        Add(x, c, (-w[c] * bc * dl) * u);
        return true;
    }

    private bool Filtered(int p, int t)
    {
        int a = _triangles[t], b = _triangles[t + 1], c = _triangles[t + 2];
        if (p == a || p == b || p == c)
        {
            return true;
        }

        var restSquared = TriangleGeometry.Closest(Rest(p), Rest(a), Rest(b), Rest(c), out _, out _);
        return restSquared < _thickness * _thickness;
    }

    // The weights of q in (a, b, c) (Ericson 3.4), for a point of the triangle.
    private static void Barycentric(Vector3d q, Vector3d a, Vector3d b, Vector3d c, out double ba, out double bb, out double bc)
    {
        Vector3d v0 = b - a, v1 = c - a, v2 = q - a;
        double d00 = Vector3d.Dot(v0, v0), d01 = Vector3d.Dot(v0, v1), d11 = Vector3d.Dot(v1, v1);
        double d20 = Vector3d.Dot(v2, v0), d21 = Vector3d.Dot(v2, v1);
        var denominator = (d00 * d11) - (d01 * d01);
        bb = ((d11 * d20) - (d01 * d21)) / denominator;
        bc = ((d00 * d21) - (d01 * d20)) / denominator;
        ba = 1.0 - bb - bc;
    }

    private static void Grow(ref Vector3d low, ref Vector3d high, Vector3d p)
    {
        low = new Vector3d(p.X < low.X ? p.X : low.X, p.Y < low.Y ? p.Y : low.Y, p.Z < low.Z ? p.Z : low.Z);
        high = new Vector3d(p.X > high.X ? p.X : high.X, p.Y > high.Y ? p.Y : high.Y, p.Z > high.Z ? p.Z : high.Z);
    }

    private Vector3d Rest(int i) => new(_rest[3 * i], _rest[(3 * i) + 1], _rest[(3 * i) + 2]);

    private static Vector3d Read(Span<double> values, int i) => new(values[3 * i], values[(3 * i) + 1], values[(3 * i) + 2]);

    private static void Add(Span<double> values, int i, Vector3d delta)
    {
        values[3 * i] += delta.X;
        values[(3 * i) + 1] += delta.Y;
        values[(3 * i) + 2] += delta.Z;
    }
}
