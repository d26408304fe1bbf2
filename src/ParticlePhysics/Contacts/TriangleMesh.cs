using System;
using System.Collections.Generic;

namespace ParticlePhysics.Contacts;

/// <summary>
/// The triangles of a mesh collider in its own frame, with what the queries need: a bounding volume hierarchy over
/// the triangles' boxes (<see cref="BoxTree"/>), each face's normal, and the angle-weighted pseudonormals of its edges
/// and vertices that give the sign of the distance (Bærentzen and Aanæs, "Signed distance computation using the angle
/// weighted pseudonormal", IEEE TVCG 2005: the sign of (p - c) . N at the closest point c, N the pseudonormal of the
/// feature c lies on, is the side of p for a closed, consistently wound mesh). Built once; read-only after.
/// </summary>
/// <remarks>
/// Every query walks the tree nearest node first with a stack of <see cref="BoxTree.MaxDepth"/> entries on the call
/// stack, so it allocates nothing and its cost grows with the log of the triangle count.
/// </remarks>
internal sealed class TriangleMesh
{
    private readonly double[] _vertices;
    private readonly int[] _triangles;
    private readonly BoxTree _tree = new();
    private readonly Vector3d[] _faceNormals;
    private readonly Vector3d[] _edgeNormals;
    private readonly Vector3d[] _vertexNormals;
    private readonly bool[] _rimEdges;
    private readonly bool[] _rimVertices;

    /// <summary>Builds the mesh; throws, naming the value, for a count, an index, a coordinate or a triangle that is not allowed.</summary>
    public TriangleMesh(double[] vertices, int[] triangles, string verticesName, string trianglesName)
    {
        Guard.NotNull(vertices, verticesName);
        Guard.NotNull(triangles, trianglesName);
        if (vertices.Length == 0 || vertices.Length % 3 != 0)
        {
            throw new ArgumentException($"{verticesName} must hold x, y, z for each vertex, a positive multiple of 3 values; got {vertices.Length}.", verticesName);
        }

        if (triangles.Length == 0 || triangles.Length % 3 != 0)
        {
            throw new ArgumentException($"{trianglesName} must hold three vertex indices for each triangle, a positive multiple of 3 values; got {triangles.Length}.", trianglesName);
        }

        for (var i = 0; i < vertices.Length; i++)
        {
            if (!double.IsFinite(vertices[i]))
            {
                throw new ArgumentException($"{verticesName}[{i}] must be finite; got {Guard.Format(vertices[i])}.", verticesName);
            }
        }

        var vertexCount = vertices.Length / 3;
        for (var i = 0; i < triangles.Length; i++)
        {
            if (triangles[i] < 0 || triangles[i] >= vertexCount)
            {
                throw new ArgumentException($"{trianglesName}[{i}] must be a vertex index from 0 to {vertexCount - 1}; got {triangles[i]}.", trianglesName);
            }
        }

        _vertices = (double[])vertices.Clone();
        _triangles = (int[])triangles.Clone();
        Count = triangles.Length / 3;
        _faceNormals = new Vector3d[Count];
        for (var t = 0; t < Count; t++)
        {
            Corners(t, out var a, out var b, out var c);
            var n = Vector3d.Cross(b - a, c - a);
            var length = n.Length;
            if (!(length > 0.0) || double.IsInfinity(length))
            {
                throw new ArgumentException(
                    $"{trianglesName}: triangle {t} ({_triangles[3 * t]}, {_triangles[(3 * t) + 1]}, {_triangles[(3 * t) + 2]}) has no area (its corners are on a line) or is too large to measure.",
                    trianglesName);
            }

            _faceNormals[t] = n / length;
        }

        _edgeNormals = new Vector3d[3 * Count];
        _vertexNormals = new Vector3d[vertexCount];
        _rimEdges = new bool[3 * Count];
        _rimVertices = new bool[vertexCount];
        IsClosed = BuildPseudonormals();
        BuildTree();
    }

    /// <summary>The number of triangles.</summary>
    public int Count { get; }

    /// <summary>
    /// True when every edge is shared by exactly two triangles that run along it in opposite directions: a closed,
    /// consistently wound surface, which has an inside.
    /// </summary>
    public bool IsClosed { get; }

    /// <summary>The vertices, x, y, z each (the mesh's own copy).</summary>
    public double[] Vertices => _vertices;

    /// <summary>The triangles, three vertex indices each (the mesh's own copy).</summary>
    public int[] Triangles => _triangles;

    /// <summary>The lower corner of the box around every vertex.</summary>
    public Vector3d Min => new(_tree.NodeMin[0], _tree.NodeMin[1], _tree.NodeMin[2]);

    /// <summary>The upper corner of the box around every vertex.</summary>
    public Vector3d Max => new(_tree.NodeMax[0], _tree.NodeMax[1], _tree.NodeMax[2]);

    /// <summary>Triangle t's corners.</summary>
    public void Corners(int t, out Vector3d a, out Vector3d b, out Vector3d c)
    {
        a = Vertex(_triangles[3 * t]);
        b = Vertex(_triangles[(3 * t) + 1]);
        c = Vertex(_triangles[(3 * t) + 2]);
    }

    /// <summary>Triangle t's unit normal, (b - a) x (c - a) normalised.</summary>
    public Vector3d FaceNormal(int t) => _faceNormals[t];

    /// <summary>
    /// The distance from p to the mesh and its gradient (<see cref="TriangleGeometry.Distance(Vector3d, Vector3d, Vector3d, Vector3d, out Vector3d)"/>
    /// of the nearest triangle), signed by the pseudonormal of the nearest feature when <paramref name="signed"/>
    /// (negative behind the surface); <paramref name="triangle"/> receives the nearest triangle. Where the nearest
    /// feature is on the rim of an open mesh (an edge of one triangle, or a vertex on such an edge), the point is beside
    /// the surface, not behind it, and the distance is unsigned: the solid behind an open mesh is bounded by the surfaces
    /// through its rim perpendicular to its faces (below a terrain, the column under it).
    /// </summary>
    public double Distance(Vector3d p, bool signed, out Vector3d gradient, out int triangle)
    {
        _ = Nearest(p, out triangle, out var feature, out var closest);
        Corners(triangle, out var a, out var b, out var c);
        if (feature == TriangleGeometry.Face)
        {
            var n = _faceNormals[triangle];
            var s = Vector3d.Dot(p - a, n);
            if (signed)
            {
                gradient = n;
                return s;
            }

            gradient = s < 0.0 ? -n : n;
            return Math.Abs(s);
        }

        var d = p - closest;
        var length = d.Length;
        if (!(length > 0.0))
        {
            gradient = _faceNormals[triangle];
            return 0.0;
        }

        gradient = d / length;
        if (signed && !OnRim(triangle, feature) && Vector3d.Dot(d, Pseudonormal(triangle, feature)) < 0.0)
        {
            gradient = -gradient;
            return -length;
        }

        return length;
    }

    /// <summary>
    /// The nearest triangle to p, the feature of it the closest point lies on and that point; returns the squared
    /// distance. Ties go to the triangle met first in the tree's fixed order, so the answer is a function of p alone.
    /// </summary>
    public double Nearest(Vector3d p, out int triangle, out int feature, out Vector3d closest)
    {
        Span<int> stack = stackalloc int[BoxTree.MaxDepth];
        var best = double.PositiveInfinity;
        triangle = 0;
        feature = TriangleGeometry.Face;
        closest = p;
        var top = 0;
        stack[top++] = 0;
        while (top > 0)
        {
            var node = stack[--top];
            var reach = _tree.DistanceTo(node, p.X, p.Y, p.Z);
            if (!(reach * reach < best))
            {
                continue;
            }

            var count = _tree.NodeCount[node];
            var first = _tree.NodeFirst[node];
            if (count > 0)
            {
                for (var k = first; k < first + count; k++)
                {
                    var t = _tree.Items[k];
                    Corners(t, out var a, out var b, out var c);
                    var squared = TriangleGeometry.Closest(p, a, b, c, out var point, out var which);
                    if (squared < best || (squared == best && t < triangle))
                    {
                        best = squared;
                        triangle = t;
                        feature = which;
                        closest = point;
                    }
                }

                continue;
            }

            PushNearestLast(stack, ref top, first, _tree.DistanceTo(first, p.X, p.Y, p.Z), _tree.DistanceTo(first + 1, p.X, p.Y, p.Z));
        }

        return best;
    }

    /// <summary>
    /// Whether some triangle comes within <paramref name="reach"/> of p: the tree is walked nearest node first, skipping
    /// every node whose box is farther, and stops at the first such triangle. A point far from the surface costs the
    /// few boxes near the root, where <see cref="Nearest"/> would walk every leaf as near as the nearest triangle.
    /// </summary>
    public bool AnyWithin(Vector3d p, double reach)
    {
        Span<int> stack = stackalloc int[BoxTree.MaxDepth];
        var squaredReach = reach * reach;
        var top = 0;
        stack[top++] = 0;
        while (top > 0)
        {
            var node = stack[--top];
            if (!(_tree.DistanceTo(node, p.X, p.Y, p.Z) <= reach))
            {
                continue;
            }

            var count = _tree.NodeCount[node];
            var first = _tree.NodeFirst[node];
            if (count > 0)
            {
                for (var k = first; k < first + count; k++)
                {
                    Corners(_tree.Items[k], out var a, out var b, out var c);
                    if (!(TriangleGeometry.Closest(p, a, b, c, out _, out _) > squaredReach))
                    {
                        return true;
                    }
                }

                continue;
            }

            PushNearestLast(stack, ref top, first, _tree.DistanceTo(first, p.X, p.Y, p.Z), _tree.DistanceTo(first + 1, p.X, p.Y, p.Z));
        }

        return false;
    }

    /// <summary>
    /// The least of the triangles' tangent bounds (<see cref="ContactSearch.SafeStep"/>) for a sphere of radius r at p
    /// moving at w along a path of bend at most A: the distance to the mesh is the least of the triangles' distances,
    /// each convex and 1-Lipschitz, so the first root of the least of their lower bounds is the first root of a lower
    /// bound of the mesh's gap. A node whose box is at distance D cannot hold a triangle with a step below the Lipschitz
    /// bound of the gap D - r at speed |w|, and is skipped once a step that short is known, or when that bound passes
    /// <paramref name="limit"/> (the rest of the search's interval): +infinity when every node is, for then nothing can
    /// be touched within it. So a particle far from the mesh costs a box or two, not a walk of the tree.
    /// </summary>
    public double SafeStep(Vector3d p, Vector3d w, double radius, double bend, double limit)
    {
        Span<int> stack = stackalloc int[BoxTree.MaxDepth];
        var speed = w.Length;
        var best = double.PositiveInfinity;
        var top = 0;
        stack[top++] = 0;
        while (top > 0)
        {
            var node = stack[--top];
            var bound = LipschitzBound(_tree.DistanceTo(node, p.X, p.Y, p.Z) - radius, speed, bend);
            if (!(bound < best) || bound > limit)
            {
                continue;
            }

            var count = _tree.NodeCount[node];
            var first = _tree.NodeFirst[node];
            if (count > 0)
            {
                for (var k = first; k < first + count; k++)
                {
                    Corners(_tree.Items[k], out var a, out var b, out var c);
                    var gap = TriangleGeometry.Distance(p, a, b, c, out var gradient) - radius;
                    best = Math.Min(best, ContactSearch.SafeStep(gap, Vector3d.Dot(w, gradient), bend));
                }

                continue;
            }

            PushNearestLast(stack, ref top, first, _tree.DistanceTo(first, p.X, p.Y, p.Z), _tree.DistanceTo(first + 1, p.X, p.Y, p.Z));
        }

        return best;
    }

    /// <summary>
    /// The first touch of a sphere of radius r (a ray for r = 0) moving from o along the unit d within
    /// <paramref name="maxDistance"/>: the nearest of the triangles' casts (<see cref="TriangleGeometry.Ray"/>,
    /// <see cref="TriangleGeometry.Sphere"/>), over the nodes whose boxes grown by r the ray enters, nearest entry first.
    /// The normal points from the surface to the sphere's centre at the touch.
    /// </summary>
    public bool Cast(Vector3d o, Vector3d d, double radius, double maxDistance, out double distance, out Vector3d normal, out int triangle)
    {
        Span<int> stack = stackalloc int[BoxTree.MaxDepth];
        var inverse = new Vector3d(1.0 / d.X, 1.0 / d.Y, 1.0 / d.Z);
        var best = maxDistance;
        var found = false;
        distance = 0.0;
        normal = Vector3d.Zero;
        triangle = -1;
        var top = 0;
        stack[top++] = 0;
        while (top > 0)
        {
            var node = stack[--top];
            if (!_tree.RayEnters(node, o, inverse, radius, best, out _))
            {
                continue;
            }

            var count = _tree.NodeCount[node];
            var first = _tree.NodeFirst[node];
            if (count > 0)
            {
                for (var k = first; k < first + count; k++)
                {
                    var t = _tree.Items[k];
                    Corners(t, out var a, out var b, out var c);
                    double at;
                    Vector3d n;
                    if (radius > 0.0)
                    {
                        if (!TriangleGeometry.Sphere(o, d, radius, a, b, c, 0.0, best, out at, out n))
                        {
                            continue;
                        }
                    }
                    else
                    {
                        if (!TriangleGeometry.Ray(o, d, a, b, c, best, out at))
                        {
                            continue;
                        }

                        n = _faceNormals[t];
                        n = Vector3d.Dot(n, d) > 0.0 ? -n : n;
                    }

                    if (!found || at < best || (at == best && t < triangle))
                    {
                        found = true;
                        best = at;
                        distance = at;
                        normal = n;
                        triangle = t;
                    }
                }

                continue;
            }

            var nearLeft = _tree.RayEnters(first, o, inverse, radius, best, out var left) ? left : double.PositiveInfinity;
            var nearRight = _tree.RayEnters(first + 1, o, inverse, radius, best, out var right) ? right : double.PositiveInfinity;
            PushNearestLast(stack, ref top, first, nearLeft, nearRight);
        }

        return found;
    }

    /// <summary>The first root of g - speed u - bend u^2 / 2 (0 for g &lt;= 0): no triangle at gap g or more closes sooner.</summary>
    private static double LipschitzBound(double gap, double speed, double bend)
    {
        var g = Math.Max(gap, 0.0);
        return 2.0 * g / (speed + Math.Sqrt((speed * speed) + (2.0 * bend * g)));
    }

    /// <summary>Pushes the two children at <paramref name="first"/>, the nearer last so that it is visited first (ties: the left one).</summary>
    private static void PushNearestLast(Span<int> stack, ref int top, int first, double left, double right)
    {
        if (right < left)
        {
            stack[top++] = first;
            stack[top++] = first + 1;
        }
        else
        {
            stack[top++] = first + 1;
            stack[top++] = first;
        }
    }

    private Vector3d Vertex(int v) => new(_vertices[3 * v], _vertices[(3 * v) + 1], _vertices[(3 * v) + 2]);

    private bool OnRim(int t, int feature) =>
        feature >= TriangleGeometry.FirstVertex ? _rimVertices[_triangles[(3 * t) + feature - TriangleGeometry.FirstVertex]]
        : feature >= TriangleGeometry.FirstEdge && _rimEdges[(3 * t) + feature - TriangleGeometry.FirstEdge];

    private Vector3d Pseudonormal(int t, int feature) =>
        feature >= TriangleGeometry.FirstVertex ? _vertexNormals[_triangles[(3 * t) + feature - TriangleGeometry.FirstVertex]]
        : feature >= TriangleGeometry.FirstEdge ? _edgeNormals[(3 * t) + feature - TriangleGeometry.FirstEdge]
        : _faceNormals[t];

    /// <summary>
    /// Each edge's pseudonormal, the sum of the normals of the triangles that share it; each vertex's, the sum of its
    /// triangles' normals weighted by their angles there. Returns whether the mesh is closed (<see cref="IsClosed"/>).
    /// </summary>
    private bool BuildPseudonormals()
    {
        var edges = new Dictionary<long, Vector3d>();
        var uses = new Dictionary<long, int>();
        var vertexCount = _vertices.Length / 3;
        for (var t = 0; t < Count; t++)
        {
            for (var e = 0; e < 3; e++)
            {
                var key = EdgeKey(_triangles[(3 * t) + e], _triangles[(3 * t) + ((e + 1) % 3)], vertexCount, out var forward);
                edges[key] = (edges.TryGetValue(key, out var sum) ? sum : Vector3d.Zero) + _faceNormals[t];
                uses[key] = (uses.TryGetValue(key, out var count) ? count : 0) + (forward ? 1 : 1 << 16);
            }

            Corners(t, out var a, out var b, out var c);
            var n = _faceNormals[t];
            _vertexNormals[_triangles[3 * t]] += TriangleGeometry.Angle(b - a, c - a) * n;
            _vertexNormals[_triangles[(3 * t) + 1]] += TriangleGeometry.Angle(c - b, a - b) * n;
            _vertexNormals[_triangles[(3 * t) + 2]] += TriangleGeometry.Angle(a - c, b - c) * n;
        }

        var closed = true;
        for (var t = 0; t < Count; t++)
        {
            for (var e = 0; e < 3; e++)
            {
                var key = EdgeKey(_triangles[(3 * t) + e], _triangles[(3 * t) + ((e + 1) % 3)], vertexCount, out _);
                _edgeNormals[(3 * t) + e] = edges[key];
                var shared = uses[key] == 1 + (1 << 16);
                closed &= shared;
                if (!shared)
                {
                    _rimEdges[(3 * t) + e] = true;
                    _rimVertices[_triangles[(3 * t) + e]] = true;
                    _rimVertices[_triangles[(3 * t) + ((e + 1) % 3)]] = true;
                }
            }
        }

        return closed;
    }

    private static long EdgeKey(int from, int to, int vertexCount, out bool forward)
    {
        forward = from < to;
        return forward ? ((long)from * vertexCount) + to : ((long)to * vertexCount) + from;
    }

    private void BuildTree()
    {
        var min = new double[3 * Count];
        var max = new double[3 * Count];
        for (var t = 0; t < Count; t++)
        {
            Corners(t, out var a, out var b, out var c);
            min[3 * t] = Math.Min(a.X, Math.Min(b.X, c.X));
            min[(3 * t) + 1] = Math.Min(a.Y, Math.Min(b.Y, c.Y));
            min[(3 * t) + 2] = Math.Min(a.Z, Math.Min(b.Z, c.Z));
            max[3 * t] = Math.Max(a.X, Math.Max(b.X, c.X));
            max[(3 * t) + 1] = Math.Max(a.Y, Math.Max(b.Y, c.Y));
            max[(3 * t) + 2] = Math.Max(a.Z, Math.Max(b.Z, c.Z));
        }

        _tree.Build(min, max, Count);
    }
}
