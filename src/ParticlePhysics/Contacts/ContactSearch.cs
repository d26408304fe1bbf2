using System;
using System.Runtime.CompilerServices;

namespace ParticlePhysics.Contacts;

/// <summary>
/// The first time within a step at which a particle's path touches an obstacle or another particle, found by safe
/// steps that never pass it (conservative advancement with a curvature bound).
/// </summary>
/// <remarks>
/// <para>
/// Let phi(s) be the gap along the path (the signed distance to the obstacle grown by the radius, or the distance of
/// two centres less the sum of the radii): the distance to a convex set is convex and 1-Lipschitz, and the path p
/// bends by at most A (a bound on |p''|), so over the next u seconds
/// phi(s + u) &gt;= phi(s) + phi'(s) u - A u^2 / 2 (convexity bounds phi(p(s + u)) below by its tangent plane at p(s),
/// |grad phi| = 1 bounds the path's departure from its tangent line, A u^2 / 2, to that much of the gap). The first root of that lower bound,
/// u = 2 phi / (b + sqrt(b^2 + 2 A phi)) with b = -phi'(s) (or (sqrt(b^2 + 2 A phi) - b) / A when the gap is opening),
/// is a step that cannot pass the first contact. It lands exactly on it for a parabola falling onto a plane (the bound
/// is then the gap itself) and converges quadratically near any transversal contact, so a handful of steps suffice; a
/// thin wall at 1000 m/s is found in one. The obstacle computes the step (<see cref="Obstacle.SafeStep"/>): this bound
/// for a convex shape, <see cref="LipschitzStep"/> for any other, the least of its triangles' bounds for a mesh.
/// </para>
/// <para>
/// A contact is a gap at most <see cref="Tolerance"/> (1e-10 m, more far from the origin) while the gap is not opening
/// (faster than <see cref="RateTolerance"/>).
/// A search that has not converged after <see cref="MaxIterations"/> steps (a path that grazes a surface) reports no
/// contact; the position projection at the end of the step then keeps the particle out.
/// </para>
/// </remarks>
internal static class ContactSearch
{
    /// <summary>The most safe steps one search takes.</summary>
    public const int MaxIterations = 64;

    /// <summary>The gap below which a path touches, in metres (far from the origin it grows with the coordinates' rounding).</summary>
    public const double Tolerance = 1e-10;

    /// <summary>
    /// A gap opening slower than this (1e-9 m/s) at contact counts as not opening: a resting contact whose rate is
    /// rounding noise would otherwise be stepped past in ever smaller steps.
    /// </summary>
    public const double RateTolerance = 1e-9;

    /// <summary>The tolerance at a point whose coordinates add up to <paramref name="magnitude"/> in absolute value.</summary>
    public static double ToleranceAt(double magnitude) => Tolerance + (1e-15 * magnitude);

    /// <summary>
    /// The first s in [<paramref name="from"/>, <paramref name="to"/>] at which particle <paramref name="i"/> of radius
    /// <paramref name="radius"/> touches <paramref name="obstacle"/> (which moves with its velocity from the step's start
    /// time <paramref name="startTime"/>), or +infinity.
    /// </summary>
    public static double FirstObstacleContact(
        ParticlePaths paths, int i, double radius, Obstacle obstacle, double startTime, double from, double to)
    {
        var bend = paths.AccelerationBound(i, from, to);
        var velocity = obstacle.Velocity;
        double wx = velocity.X, wy = velocity.Y, wz = velocity.Z;
        var offset = obstacle.OffsetAt(startTime);
        double ox = offset.X, oy = offset.Y, oz = offset.Z;
        var s = from;
        for (var iteration = 0; iteration < MaxIterations; iteration++)
        {
            // The particle relative to the obstacle, which has moved by offset + w s since the start of the step.
            paths.Evaluate(i, s, out var px, out var py, out var pz, out var vx, out var vy, out var vz);
            double qx = px - ox - (wx * s), qy = py - oy - (wy * s), qz = pz - oz - (wz * s);
            var gap = obstacle.Distance(qx, qy, qz, out var nx, out var ny, out var nz) - radius;
            var rate = ((vx - wx) * nx) + ((vy - wy) * ny) + ((vz - wz) * nz);
            if (gap <= ToleranceAt(Math.Abs(qx) + Math.Abs(qy) + Math.Abs(qz)) && rate <= RateTolerance)
            {
                return s;
            }

            s += obstacle.SafeStep(qx, qy, qz, vx - wx, vy - wy, vz - wz, radius, gap, rate, bend, to - s);
            if (!(s <= to))
            {
                return double.PositiveInfinity;
            }
        }

        return double.PositiveInfinity;
    }

    /// <summary>The first s in [from, to] at which particles <paramref name="i"/> and <paramref name="j"/> touch, or +infinity.</summary>
    public static double FirstPairContact(ParticlePaths paths, int i, int j, double reach, double from, double to)
    {
        var bend = paths.RelativeAccelerationBound(i, j, from, to);
        var s = from;
        for (var iteration = 0; iteration < MaxIterations; iteration++)
        {
            paths.Evaluate(i, s, out var ax, out var ay, out var az, out var avx, out var avy, out var avz);
            paths.Evaluate(j, s, out var bx, out var by, out var bz, out var bvx, out var bvy, out var bvz);
            var gap = PairNormal.Of(ax - bx, ay - by, az - bz, i, j, out var nx, out var ny, out var nz) - reach;
            var rate = ((avx - bvx) * nx) + ((avy - bvy) * ny) + ((avz - bvz) * nz);
            if (gap <= ToleranceAt(Math.Abs(ax) + Math.Abs(ay) + Math.Abs(az)) && rate <= RateTolerance)
            {
                return s;
            }

            s += SafeStep(gap, rate, bend);
            if (!(s <= to))
            {
                return double.PositiveInfinity;
            }
        }

        return double.PositiveInfinity;
    }

    /// <summary>
    /// The first u &gt; 0 at which gap + rate u - bend u^2 / 2 can reach 0 (a lower bound of the gap along the path):
    /// infinity when it never can.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static double SafeStep(double gap, double rate, double bend)
    {
        var g = Math.Max(gap, 0.0);
        var b = -rate;
        var root = Math.Sqrt((b * b) + (2.0 * bend * g));
        if (b > 0.0)
        {
            return 2.0 * g / (b + root);
        }

        return bend > 0.0 ? (root - b) / bend : double.PositiveInfinity;
    }

    /// <summary>
    /// The step for a gap that is only 1-Lipschitz (not convex): along a path of speed at most <paramref name="speed"/>
    /// relative to the shape and bend <paramref name="bend"/>, the point moves at most speed u + bend u^2 / 2 in u
    /// seconds, so the gap stays above gap - speed u - bend u^2 / 2, whose first root is the step. Within
    /// <see cref="Tolerance"/> of the surface (touching, and leaving since the search did not stop there) the local
    /// tangent bound of <see cref="SafeStep"/> is taken instead, which the Lipschitz bound would hold at 0.
    /// </summary>
    public static double LipschitzStep(double gap, double rate, double speed, double bend)
    {
        if (!(gap > Tolerance))
        {
            return SafeStep(gap, rate, bend);
        }

        return 2.0 * gap / (speed + Math.Sqrt((speed * speed) + (2.0 * bend * gap)));
    }
}
