using System;

namespace ParticlePhysics.Contacts;

/// <summary>The edge-edge half of the cloth's self-collision.</summary>
/// <remarks>
/// Two triangles can cross with every particle farther than h from the other's face: in a crease sharper than the
/// thickness, an edge passes through another edge. So every two edges that share no particle are also kept h apart.
/// With P = (1 - s) x_a + s x_b and Q = (1 - t) x_c + t x_d their closest points at the end of the substep and
/// d = P - Q, the constraint is C = u . d - h &gt;= 0 with u = d / |d| when d points the way it did at the start
/// (the same s and t on the start's edges), and u = -d / |d| when it turned over, which is a crossing in the substep:
/// the edges are put back on their own sides. Gradients (1 - s) u, s u, -(1 - t) u, -t u; the same zero-compliance
/// step as the particle-triangle one. Candidates: the edges' boxes over the substep, grown by h, in a grid; each edge's
/// own box the query, each pair once.
/// </remarks>
public sealed partial class ClothSelfCollision
{
    private void ProjectEdges(Span<double> x, Span<double> start, Span<double> w, double reach, double cell)
    {
        // The edges' boxes over the substep grown by h in the grid (rebuilt: the particle pass moved them), each
        // edge's own box the query, each pair once from its first edge.
        var edges = _edges.Length / 2;
        _grid.Begin(edges, cell);
        for (var e = 0; e < edges; e++)
        {
            var (low, high) = EdgeBox(x, start, 2 * e);
            _grid.Set(e, low - new Vector3d(_thickness, _thickness, _thickness), high + new Vector3d(_thickness, _thickness, _thickness));
        }

        _grid.End();
        for (var e = 0; e < edges; e++)
        {
            int a = _edges[2 * e], b = _edges[(2 * e) + 1];
            var (low, high) = EdgeBox(x, start, 2 * e);
            foreach (var f in _grid.Overlapping(low, high))
            {
                int c = _edges[2 * f], d = _edges[(2 * f) + 1];
                if (f > e && c != a && c != b && d != a && d != b && ProjectEdgePair(x, start, w, 2 * e, 2 * f, reach))
                {
                    _contacts++;
                }
            }
        }
    }

    private (Vector3d Low, Vector3d High) EdgeBox(Span<double> x, Span<double> start, int e)
    {
        int a = _edges[e], b = _edges[e + 1];
        Vector3d low = Read(x, a), high = low;
        Grow(ref low, ref high, Read(x, b));
        Grow(ref low, ref high, Read(start, a));
        Grow(ref low, ref high, Read(start, b));
        return (low, high);
    }

    private bool ProjectEdgePair(Span<double> x, Span<double> start, Span<double> w, int e, int f, double reach)
    {
        int a = _edges[e], b = _edges[e + 1], c = _edges[f], d = _edges[f + 1];
        Vector3d xa = Read(x, a), xb = Read(x, b), xc = Read(x, c), xd = Read(x, d);
        ClosestOnSegments(xa, xb, xc, xd, out var s, out var t);
        var between = ((1.0 - s) * xa) + (s * xb) - (((1.0 - t) * xc) + (t * xd));
        var startBetween = ((1.0 - s) * Read(start, a)) + (s * Read(start, b)) - (((1.0 - t) * Read(start, c)) + (t * Read(start, d)));
        var squared = Vector3d.Dot(between, between);
        var turned = Vector3d.Dot(between, startBetween) < 0.0;
        if ((!turned && !(squared < _thickness * _thickness)) || (turned && !(startBetween.Length <= reach)))
        {
            return false; // apart and not crossed, or turned over from afar (not a crossing of these two)
        }

        var distance = Math.Sqrt(squared);
        Vector3d u;
        if (distance > 0.0)
        {
            u = (turned ? -1.0 : 1.0) * between / distance;
        }
        else
        {
            var startDistance = startBetween.Length;
            if (!(startDistance > 0.0))
            {
                return false; // touching at the start and the end: no side to put them on
            }

            u = startBetween / startDistance;
        }

        var gap = Vector3d.Dot(u, between) - _thickness;
        if (!(gap < 0.0) || RestNeighbourEdges(a, b, c, d))
        {
            return false;
        }

        var weights = ((1.0 - s) * (1.0 - s) * w[a]) + (s * s * w[b]) + ((1.0 - t) * (1.0 - t) * w[c]) + (t * t * w[d]);
        if (!(weights > 0.0))
        {
            return false;
        }

        var dl = -gap / weights;
        Add(x, a, (w[a] * (1.0 - s) * dl) * u);
        Add(x, b, (w[b] * s * dl) * u);
        Add(x, c, (-w[c] * (1.0 - t) * dl) * u);
        Add(x, d, (-w[d] * t * dl) * u);
        return true;
    }

    private bool RestNeighbourEdges(int a, int b, int c, int d)
    {
        ClosestOnSegments(Rest(a), Rest(b), Rest(c), Rest(d), out var s, out var t);
        var between = ((1.0 - s) * Rest(a)) + (s * Rest(b)) - (((1.0 - t) * Rest(c)) + (t * Rest(d)));
        return Vector3d.Dot(between, between) < _thickness * _thickness;
    }

    /// <summary>
    /// The parameters s and t in [0, 1] of the closest points of the segments pq and rs (Ericson, "Real-Time Collision
    /// Detection", 5.1.9), parallel segments taking s = 0 unless clamping moves it.
    /// </summary>
    private static void ClosestOnSegments(Vector3d p, Vector3d q, Vector3d r, Vector3d sEnd, out double s, out double t)
    {
        var d1 = q - p;
        var d2 = sEnd - r;
        var offset = p - r;
        double a = Vector3d.Dot(d1, d1), e = Vector3d.Dot(d2, d2), f = Vector3d.Dot(d2, offset);
        var c = Vector3d.Dot(d1, offset);
        var b = Vector3d.Dot(d1, d2);
        var denominator = (a * e) - (b * b);
        s = denominator > 0.0 ? Clamp01(((b * f) - (c * e)) / denominator) : 0.0;
        t = ((b * s) + f) / e;
        if (t < 0.0)
        {
            t = 0.0;
            s = Clamp01(-c / a);
        }
        else if (t > 1.0)
        {
            t = 1.0;
            s = Clamp01((b - c) / a);
        }
    }

    private static double Clamp01(double value) => value < 0.0 ? 0.0 : value > 1.0 ? 1.0 : value;

    /// <summary>The unique edges of the triangles, two particles each (the smaller first), in order of first appearance.</summary>
    private static int[] Edges(int[] triangles, int count)
    {
        var seen = new System.Collections.Generic.HashSet<long>();
        var edges = new System.Collections.Generic.List<int>();
        for (var k = 0; k < triangles.Length; k += 3)
        {
            for (var j = 0; j < 3; j++)
            {
                int p = triangles[k + j], q = triangles[k + ((j + 1) % 3)];
                int lo = Math.Min(p, q), hi = Math.Max(p, q);
                if (seen.Add(((long)lo * count) + hi))
                {
                    edges.Add(lo);
                    edges.Add(hi);
                }
            }
        }

        return edges.ToArray();
    }
}
