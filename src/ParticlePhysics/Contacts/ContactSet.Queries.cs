using System;

namespace ParticlePhysics.Contacts;

/// <summary>
/// Queries of the scene the contact set sees: a ray or a sphere cast against its obstacles and a world's particles (the
/// closest hit), and the obstacles and particles that overlap a sphere. None allocates.
/// </summary>
public sealed partial class ContactSet
{
    /// <summary>
    /// The closest thing the ray from <paramref name="origin"/> along <paramref name="direction"/> meets within
    /// <paramref name="maxDistance"/>: an obstacle where it is at the world's time (<see cref="Obstacle.Cast"/>: closed
    /// forms for planes and spheres, the exact triangle for meshes and height fields) or a particle of
    /// <paramref name="world"/> with a radius (a ball of that radius). Only what <paramref name="filter"/> accepts
    /// (<see cref="CollisionFilter.Accepts"/>; by default everything). Ties go to the obstacle, then the lower index.
    /// </summary>
    /// <param name="world">The particles, or null for the obstacles alone.</param>
    /// <param name="origin">The ray's start, in metres.</param>
    /// <param name="direction">Its direction, any finite length but 0 (normalised here).</param>
    /// <param name="maxDistance">How far it reaches, &gt;= 0 (may be infinite).</param>
    /// <param name="hit">Receives the closest hit.</param>
    /// <param name="filter">Which layers the ray meets.</param>
    /// <returns>Whether anything was hit.</returns>
    /// <exception cref="ArgumentException">A non-finite origin, a zero or non-finite direction, or a negative or NaN distance.</exception>
    public bool Raycast(ParticleWorld? world, Vector3d origin, Vector3d direction, double maxDistance, out QueryHit hit, CollisionFilter filter = default) =>
        Cast(world, origin, direction, 0.0, maxDistance, out hit, filter);

    /// <summary>
    /// The closest thing a sphere of radius <paramref name="radius"/> moving from <paramref name="origin"/> along
    /// <paramref name="direction"/> touches within <paramref name="maxDistance"/> (as <see cref="Raycast"/>; a particle
    /// of radius r is touched when the centres are radius + r apart). <see cref="QueryHit.Point"/> is the touch on the
    /// surface hit.
    /// </summary>
    /// <exception cref="ArgumentException">As <see cref="Raycast"/>, or a negative or non-finite radius.</exception>
    public bool SphereCast(
        ParticleWorld? world, Vector3d origin, Vector3d direction, double radius, double maxDistance, out QueryHit hit, CollisionFilter filter = default)
    {
        Guard.NonNegativeFinite(radius, nameof(radius));
        return Cast(world, origin, direction, radius, maxDistance, out hit, filter);
    }

    /// <summary>
    /// The obstacles and particles that a sphere of radius <paramref name="radius"/> at <paramref name="centre"/>
    /// touches or overlaps (an obstacle whose signed distance from the centre is at most the radius, a particle whose
    /// centre is within the two radii), obstacles first, each in index order. Fills <paramref name="hits"/> with the
    /// first of them and returns how many there are in all (more than the span holds when it is too short).
    /// </summary>
    /// <exception cref="ArgumentException">A non-finite centre, or a negative or non-finite radius.</exception>
    public int Overlap(ParticleWorld? world, Vector3d centre, double radius, Span<QueryHit> hits, CollisionFilter filter = default)
    {
        Guard.Finite(centre, nameof(centre));
        Guard.NonNegativeFinite(radius, nameof(radius));
        var time = world?.Time ?? 0.0;
        var found = 0;
        for (var k = 0; k < _obstacles.Count; k++)
        {
            var obstacle = _obstacles[k];
            if (!obstacle.Filter.Accepts(filter))
            {
                continue;
            }

            var offset = obstacle.OffsetAt(time);
            var d = obstacle.SignedDistance(centre - offset, out var normal);
            if (d <= radius)
            {
                if (found < hits.Length)
                {
                    hits[found] = new QueryHit(k, -1, -1, centre - (d * normal), normal, d);
                }

                found++;
            }
        }

        for (var i = 0; world != null && i < world.Count; i++)
        {
            if (!ParticleFilter(i).Accepts(filter))
            {
                continue;
            }

            var r = world.GetRadius(i);
            var p = world.GetPosition(i);
            var between = centre - p;
            var length = between.Length;
            if (length <= radius + r)
            {
                if (found < hits.Length)
                {
                    _ = SphereObstacle.PointDistance(between.X, between.Y, between.Z, out var nx, out var ny, out var nz);
                    var normal = new Vector3d(nx, ny, nz);
                    hits[found] = new QueryHit(-1, i, -1, p + (r * normal), normal, length - r);
                }

                found++;
            }
        }

        return found;
    }

    private bool Cast(ParticleWorld? world, Vector3d origin, Vector3d direction, double radius, double maxDistance, out QueryHit hit, CollisionFilter filter)
    {
        Guard.Finite(origin, nameof(origin));
        var d = UnitVectors.Normalized(direction, nameof(direction));
        if (!(maxDistance >= 0.0))
        {
            throw new ArgumentOutOfRangeException(nameof(maxDistance), maxDistance, $"maxDistance must be >= 0 (infinity allowed); got {Guard.Format(maxDistance)}.");
        }

        var time = world?.Time ?? 0.0;
        var best = maxDistance;
        var found = false;
        hit = default;
        for (var k = 0; k < _obstacles.Count; k++)
        {
            var obstacle = _obstacles[k];
            if (!obstacle.Filter.Accepts(filter))
            {
                continue;
            }

            var offset = obstacle.OffsetAt(time);
            if (obstacle.Cast(origin - offset, d, radius, best, out var distance, out var normal, out var feature)
                && (!found || distance < best))
            {
                found = true;
                best = distance;
                hit = new QueryHit(k, -1, feature, origin + (distance * d) - (radius * normal), normal, distance);
            }
        }

        for (var i = 0; world != null && i < world.Count; i++)
        {
            var r = world.GetRadius(i);
            if ((r == 0.0 && radius == 0.0) || !ParticleFilter(i).Accepts(filter))
            {
                continue;
            }

            var p = world.GetPosition(i);
            if (ShapeCasts.Ball(p, r, origin, d, radius, best, out var distance, out var normal) && (!found || distance < best))
            {
                found = true;
                best = distance;
                hit = new QueryHit(-1, i, -1, origin + (distance * d) - (radius * normal), normal, distance);
            }
        }

        return found;
    }
}
