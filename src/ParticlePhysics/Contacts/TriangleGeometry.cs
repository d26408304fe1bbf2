using System;
using System.Runtime.CompilerServices;

namespace ParticlePhysics.Contacts;

/// <summary>
/// One triangle's geometry for the mesh colliders: the closest point and which feature it lies on, a ray's crossing,
/// and the cast of a sphere. Every function uses only + - * / and square roots, so it gives the same bits on every
/// runtime.
/// </summary>
internal static class TriangleGeometry
{
    /// <summary>The closest point is inside the face.</summary>
    public const int Face = 0;

    /// <summary>Features 1, 2, 3: the edges ab, bc, ca; 4, 5, 6: the vertices a, b, c.</summary>
    public const int FirstEdge = 1;

    /// <summary>The first vertex feature (a); b and c follow.</summary>
    public const int FirstVertex = 4;

    /// <summary>
    /// The point of the triangle (a, b, c) closest to p and the feature it lies on (Ericson, "Real-Time Collision
    /// Detection", 5.1.5: p's Voronoi region among the vertices, the edges and the face, from the signs of six dot
    /// products). Returns the squared distance.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static double Closest(Vector3d p, Vector3d a, Vector3d b, Vector3d c, out Vector3d closest, out int feature)
    {
        var ab = b - a;
        var ac = c - a;
        var ap = p - a;
        var d1 = Vector3d.Dot(ab, ap);
        var d2 = Vector3d.Dot(ac, ap);
        if (d1 <= 0.0 && d2 <= 0.0)
        {
            return Done(p, a, FirstVertex, out closest, out feature);
        }

        var bp = p - b;
        var d3 = Vector3d.Dot(ab, bp);
        var d4 = Vector3d.Dot(ac, bp);
        if (d3 >= 0.0 && d4 <= d3)
        {
            return Done(p, b, FirstVertex + 1, out closest, out feature);
        }

        var vc = (d1 * d4) - (d3 * d2);
        if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
        {
            return Done(p, a + ((d1 / (d1 - d3)) * ab), FirstEdge, out closest, out feature);
        }

        var cp = p - c;
        var d5 = Vector3d.Dot(ab, cp);
        var d6 = Vector3d.Dot(ac, cp);
        if (d6 >= 0.0 && d5 <= d6)
        {
            return Done(p, c, FirstVertex + 2, out closest, out feature);
        }

        var vb = (d5 * d2) - (d1 * d6);
        if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
        {
            return Done(p, a + ((d2 / (d2 - d6)) * ac), FirstEdge + 2, out closest, out feature);
        }

        var va = (d3 * d6) - (d5 * d4);
        if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
        {
            return Done(p, b + (((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b)), FirstEdge + 1, out closest, out feature);
        }

        var denominator = 1.0 / (va + vb + vc);
        return Done(p, a + ((vb * denominator) * ab) + ((vc * denominator) * ac), Face, out closest, out feature);
    }

    /// <summary>The unit normal of (a, b, c), (b - a) x (c - a) normalised: counter-clockwise seen from its front.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector3d Normal(Vector3d a, Vector3d b, Vector3d c)
    {
        var n = Vector3d.Cross(b - a, c - a);
        return n / n.Length;
    }

    /// <summary>
    /// The unsigned distance from p to the triangle and its gradient (from the triangle towards p): in the face's
    /// region the plane's distance |(p - a) . n| and +-n, which are exact there where (p - c) / |p - c| would lose
    /// digits when p is very near; elsewhere |p - c| and (p - c) / |p - c|; n itself on the triangle.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static double Distance(Vector3d p, Vector3d a, Vector3d b, Vector3d c, out Vector3d gradient)
    {
        _ = Closest(p, a, b, c, out var closest, out var feature);
        return Distance(p, a, b, c, closest, feature, out gradient);
    }

    /// <summary>The same, from a closest point already found.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static double Distance(Vector3d p, Vector3d a, Vector3d b, Vector3d c, Vector3d closest, int feature, out Vector3d gradient)
    {
        if (feature == Face)
        {
            var n = Normal(a, b, c);
            var s = Vector3d.Dot(p - a, n);
            gradient = s < 0.0 ? -n : n;
            return Math.Abs(s);
        }

        var d = p - closest;
        var length = d.Length;
        gradient = length > 0.0 ? d / length : Normal(a, b, c);
        return length;
    }

    /// <summary>
    /// Where the ray o + t d, t in [0, <paramref name="limit"/>], crosses the triangle from either side (Möller and
    /// Trumbore: t and the barycentric u, v from Cramer's rule on a + u (b - a) + v (c - a) = o + t d); false if it does
    /// not, or runs along its plane.
    /// </summary>
    public static bool Ray(Vector3d o, Vector3d d, Vector3d a, Vector3d b, Vector3d c, double limit, out double t)
    {
        t = 0.0;
        var e1 = b - a;
        var e2 = c - a;
        var pv = Vector3d.Cross(d, e2);
        var determinant = Vector3d.Dot(e1, pv);
        if (determinant == 0.0)
        {
            return false;
        }

        var inverse = 1.0 / determinant;
        var tv = o - a;
        var u = Vector3d.Dot(tv, pv) * inverse;
        if (u < 0.0 || u > 1.0)
        {
            return false;
        }

        var qv = Vector3d.Cross(tv, e1);
        var v = Vector3d.Dot(d, qv) * inverse;
        if (v < 0.0 || u + v > 1.0)
        {
            return false;
        }

        t = Vector3d.Dot(e2, qv) * inverse;
        return t >= 0.0 && t <= limit;
    }

    /// <summary>
    /// The first t in [<paramref name="from"/>, <paramref name="limit"/>] at which a sphere of radius r at o + t d
    /// touches the triangle (radius &gt; 0): Newton's steps from the left on the convex g(t) = dist(o + t d) - r, which
    /// never pass its first root (<see cref="ShapeCasts"/>).
    /// </summary>
    public static bool Sphere(
        Vector3d o, Vector3d d, double radius, Vector3d a, Vector3d b, Vector3d c, double from, double limit, out double t, out Vector3d normal)
    {
        t = from;
        var scale = Math.Abs(o.X) + Math.Abs(o.Y) + Math.Abs(o.Z);
        for (var iteration = 0; iteration < 100; iteration++)
        {
            var gap = Distance(o + (t * d), a, b, c, out normal) - radius;
            if (!(gap > 0.0))
            {
                return t <= limit;
            }

            var rate = Vector3d.Dot(d, normal);
            if (!(rate < 0.0))
            {
                return false;
            }

            var step = gap / -rate;
            if (!(t + step <= limit))
            {
                return false;
            }

            t += step;
            if (step <= 1e-16 * (scale + t))
            {
                _ = Distance(o + (t * d), a, b, c, out normal);
                return true;
            }
        }

        normal = Vector3d.Zero;
        return false;
    }

    /// <summary>
    /// The angle between two vectors, in radians, 2 atan(|u - v| / |u + v|) for unit u, v (accurate at every angle,
    /// where acos loses digits near 0 and pi), with an arctangent of our own so that the bits do not depend on the
    /// runtime's library.
    /// </summary>
    public static double Angle(Vector3d u, Vector3d v)
    {
        u /= u.Length;
        v /= v.Length;
        var difference = (u - v).Length;
        var sum = (u + v).Length;
        return sum >= difference ? 2.0 * Atan(difference / sum) : Math.PI - (2.0 * Atan(sum / difference));
    }

    /// <summary>
    /// atan(x) for 0 &lt;= x &lt;= 1: two halvings, atan(x) = 2 atan(x / (1 + sqrt(1 + x^2))), bring x below
    /// tan(pi / 16) &lt; 0.2, where the series x (1 - y / 3 + y^2 / 5 - ...), y = x^2, to y^20 leaves less than 1e-30.
    /// </summary>
    private static double Atan(double x)
    {
        x /= 1.0 + Math.Sqrt(1.0 + (x * x));
        x /= 1.0 + Math.Sqrt(1.0 + (x * x));
        var y = x * x;
        var sum = 0.0;
        for (var k = 20; k >= 0; k--)
        {
            sum = ((k % 2 == 0 ? 1.0 : -1.0) / ((2 * k) + 1)) + (y * sum);
        }

        return 4.0 * x * sum;
    }

    private static double Done(Vector3d p, Vector3d point, int which, out Vector3d closest, out int feature)
    {
        closest = point;
        feature = which;
        var d = p - point;
        return Vector3d.Dot(d, d);
    }
}
