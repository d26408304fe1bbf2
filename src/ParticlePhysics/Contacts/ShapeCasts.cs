using System;

namespace ParticlePhysics.Contacts;

/// <summary>
/// Casts of a sphere (a ray for radius 0) against shapes given by their distance: the closed forms for a plane and a
/// sphere, and the march every other shape uses by default (<see cref="Obstacle.Cast"/>).
/// </summary>
/// <remarks>
/// The march: along the ray o + t d the gap g(t) = phi(o + t d) - r. For a convex shape g is convex in t, so Newton's
/// step from the left, t += g / -g', never passes the first root (a convex function lies above its tangent) and
/// converges to it quadratically for a ray that crosses the surface; a slope g' &gt;= 0 with g &gt; 0 means g never
/// falls to 0 ahead, a miss. For any other 1-Lipschitz phi, t += g (sphere tracing) is safe for the same reason as
/// the contact search's Lipschitz step, and converges geometrically.
/// </remarks>
internal static class ShapeCasts
{
    private const int MaxIterations = 200;

    /// <summary>The march of the remarks against <paramref name="obstacle"/> where its parameters put it.</summary>
    public static bool March(
        Obstacle obstacle, Vector3d origin, Vector3d direction, double radius, double maxDistance, out double distance, out Vector3d normal)
    {
        var convex = obstacle.IsConvex;
        var t = 0.0;
        var scale = Math.Abs(origin.X) + Math.Abs(origin.Y) + Math.Abs(origin.Z);
        for (var iteration = 0; iteration < MaxIterations; iteration++)
        {
            var p = origin + (t * direction);
            var gap = obstacle.Distance(p.X, p.Y, p.Z, out var nx, out var ny, out var nz) - radius;
            normal = new Vector3d(nx, ny, nz);
            distance = t;
            var rate = Vector3d.Dot(direction, normal);
            if (!(gap > 0.0))
            {
                return true;
            }

            double step;
            if (convex)
            {
                if (!(rate < 0.0))
                {
                    return false;
                }

                step = gap / -rate;
            }
            else
            {
                if (gap <= 1e-12 * (1.0 + scale + t))
                {
                    return true;
                }

                step = gap;
            }

            if (!(t + step <= maxDistance))
            {
                return false;
            }

            if (step <= 1e-16 * (scale + t))
            {
                // Newton's steps are down to the rounding of t: this is the root.
                distance = t + step;
                return true;
            }

            t += step;
        }

        distance = 0.0;
        normal = Vector3d.Zero;
        return false;
    }

    /// <summary>A sphere of radius <paramref name="radius"/> cast against the ball of radius <paramref name="ball"/> at <paramref name="centre"/>.</summary>
    public static bool Ball(
        Vector3d centre, double ball, Vector3d origin, Vector3d direction, double radius, double maxDistance, out double distance, out Vector3d normal)
    {
        // |o + t d - c|^2 = R^2 with R = ball + radius: t^2 + 2 b t + c0 = 0, b = (o - c) . d, c0 = |o - c|^2 - R^2;
        // the smaller root c0 / (-b + sqrt(b^2 - c0)), which does not cancel when the ray starts near the surface.
        var reach = ball + radius;
        var m = origin - centre;
        var b = Vector3d.Dot(m, direction);
        var c0 = Vector3d.Dot(m, m) - (reach * reach);
        distance = 0.0;
        normal = Vector3d.Zero;
        if (!(c0 > 0.0))
        {
            _ = SphereObstacle.PointDistance(m.X, m.Y, m.Z, out var sx, out var sy, out var sz);
            normal = new Vector3d(sx, sy, sz);
            return true;
        }

        var discriminant = (b * b) - c0;
        if (!(b < 0.0) || !(discriminant >= 0.0))
        {
            return false;
        }

        var t = c0 / (Math.Sqrt(discriminant) - b);
        if (!(t <= maxDistance))
        {
            return false;
        }

        var at = m + (t * direction);
        _ = SphereObstacle.PointDistance(at.X, at.Y, at.Z, out var nx, out var ny, out var nz);
        distance = t;
        normal = new Vector3d(nx, ny, nz);
        return true;
    }
}
