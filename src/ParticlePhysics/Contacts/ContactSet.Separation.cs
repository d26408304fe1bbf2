using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Contacts;

/// <summary>
/// Stage 5 of <see cref="ContactSet.Resolve"/>: what still overlaps at the end of the step is pushed apart (stacks,
/// piles, a particle pressed against an obstacle by its neighbours), and the approaching velocity taken out.
/// </summary>
public sealed partial class ContactSet
{
    /// <summary>The separation passes stop once none moves anything by more than this, in metres (the contract's bound).</summary>
    private const double SeparationTolerance = 1e-6;

    /// <summary>
    /// Separation at the end of the step: Gauss-Seidel passes over the contacts that touch or nearly touch (particle
    /// pairs, then particles on obstacles): overlapping particles are pushed apart along their line of centres in inverse
    /// proportion to their masses, a particle inside an obstacle is put on its surface, and the approaching normal
    /// velocity is taken out (with Coulomb friction bounded by mu times that change). The passes stop once nothing
    /// moves by more than 1e-6 m.
    /// </summary>
    /// <remarks>
    /// A stack of k particles needs about k plain passes, since each passes a push one layer on. So the last pass is
    /// shock propagation (Guendelman, Bridson and Fedkiw, "Nonconvex rigid bodies with stacking", 2003): particles are
    /// ranked by how many contacts separate them from an obstacle (those on an obstacle rank 0), pairs are taken in
    /// rank order, and in each the particle nearer the support counts as immovable, so one pass carries the support up
    /// the whole stack. A final pass over every particle and every obstacle then keeps each particle out of the
    /// obstacles (the contract's 1e-6 m), whatever the passes before did.
    /// </remarks>
    private void Separate(in ConstraintContext context, int iterations)
    {
        var n = context.Count;
        var inverseMasses = context.InverseMasses.ForReading();
        var radii = context.Radii.ForReading();
        var time = context.Time + context.Dt;
        var first = _pairs.First;
        var second = _pairs.Second;
        var pairs = first.Length;
        CollectObstacleContacts(in context, time);
        CountContacts(_near.Count);
        for (var pass = 0; pass < iterations; pass++)
        {
            var moved = 0.0;
            for (var p = 0; p < pairs; p++)
            {
                var a = first[p];
                var b = second[p];
                moved = Math.Max(moved, SeparatePair(in context, a, b, inverseMasses[a], inverseMasses[b], radii));
            }

            for (var c = 0; c < _near.Count; c++)
            {
                var i = _near.Particle(c);
                moved = Math.Max(moved, SeparateFromObstacle(in context, i, _near.Obstacle(c), Radius(radii, i), time));
            }

            if (moved <= SeparationTolerance)
            {
                pairs = 0; // converged: no shock pass needed
                break;
            }
        }

        if (pairs > 0)
        {
            PropagateShock(in context, first, second, inverseMasses, radii);
        }

        var x = context.Positions;
        for (var i = 0; i < n && _obstacles.Count > 0; i++)
        {
            if (inverseMasses[i] == 0.0)
            {
                continue;
            }

            // Every obstacle it may be inside, in index order; a push out of one moves it, so the candidates after that
            // one are asked again from where it is now (as the loop over every obstacle would meet them).
            var radius = Radius(radii, i);
            var candidates = ObstaclesNear(i, Read(x, i), radius, -1);
            for (var c = 0; c < candidates; c++)
            {
                var k = _candidates[c];
                if (SeparateFromObstacle(in context, i, k, radius, time) != 0.0)
                {
                    candidates = ObstaclesNear(i, Read(x, i), radius, k);
                    c = -1;
                }
            }
        }
    }

    /// <summary>The (particle, obstacle) pairs within a quarter radius (or 1e-6 m) of touching at the end of the step.</summary>
    private void CollectObstacleContacts(in ConstraintContext context, double time)
    {
        var n = context.Count;
        var inverseMasses = context.InverseMasses.ForReading();
        var radii = context.Radii.ForReading();
        var x = context.Positions;
        _near.Clear();
        for (var i = 0; i < n && _obstacles.Count > 0; i++)
        {
            if (inverseMasses[i] == 0.0)
            {
                continue;
            }

            var radius = Radius(radii, i);
            var candidates = ObstaclesNear(i, Read(x, i), (1.25 * radius) + 1e-6, -1);
            for (var c = 0; c < candidates; c++)
            {
                var k = _candidates[c];
                var obstacle = _obstacles[k];
                var q = Read(x, i) - obstacle.OffsetAt(time);
                var gap = obstacle.Distance(q.X, q.Y, q.Z, out _, out _, out _) - radius;
                if (gap < (0.25 * radius) + 1e-6)
                {
                    _near.Add(i, k);
                }
            }
        }
    }

    /// <summary>One pass over the pairs in order of rank from the support (<see cref="ShockOrder"/>), the particle nearer it held still.</summary>
    private void PropagateShock(
        in ConstraintContext context, Span<int> first, Span<int> second, Span<double> inverseMasses, Span<double> radii)
    {
        _shock.Order(
            context.Count, first, second, inverseMasses, _near, context.Positions, radii, RestingMargin, DefaultMaxCandidatePairs);
        for (var k = 0; k < first.Length; k++)
        {
            var p = _shock.PairAt(k);
            var a = first[p];
            var b = second[p];
            var wa = inverseMasses[a];
            var wb = inverseMasses[b];
            if (_shock.Rank(a) < _shock.Rank(b))
            {
                wa = 0.0;
            }
            else if (_shock.Rank(b) < _shock.Rank(a))
            {
                wb = 0.0;
            }

            _ = SeparatePair(in context, a, b, wa, wb, radii);
        }
    }

    /// <summary>Pushes a and b apart if they overlap (weights w: inverse masses, or 0 for a particle held still); returns the overlap.</summary>
    private double SeparatePair(in ConstraintContext context, int a, int b, double wa, double wb, Span<double> radii)
    {
        var w = wa + wb;
        if (w == 0.0)
        {
            return 0.0;
        }

        var x = context.Positions;
        int ia = 3 * a, ib = 3 * b;
        double dx = x[ia] - x[ib], dy = x[ia + 1] - x[ib + 1], dz = x[ia + 2] - x[ib + 2];
        var reach = Radius(radii, a) + Radius(radii, b);
        var squared = (dx * dx) + (dy * dy) + (dz * dz);
        if (!(squared < reach * reach))
        {
            return 0.0;
        }

        var distance = PairNormal.Of(dx, dy, dz, a, b, out var nx, out var ny, out var nz);
        var overlap = reach - distance;
        var sa = overlap * wa / w;
        var sb = overlap * wb / w;
        x[ia] += sa * nx;
        x[ia + 1] += sa * ny;
        x[ia + 2] += sa * nz;
        x[ib] -= sb * nx;
        x[ib + 1] -= sb * ny;
        x[ib + 2] -= sb * nz;
        var v = context.Velocities;
        double rx = v[ia] - v[ib], ry = v[ia + 1] - v[ib + 1], rz = v[ia + 2] - v[ib + 2];
        var un = (rx * nx) + (ry * ny) + (rz * nz);
        if (un < 0.0)
        {
            // Inelastic: the normal impulse j = -u_n / w; friction up to mu j against the relative tangential velocity.
            var j = -un / w;
            double ix = j * nx, iy = j * ny, iz = j * nz;
            double tx = rx - (un * nx), ty = ry - (un * ny), tz = rz - (un * nz);
            var speed = Math.Sqrt((tx * tx) + (ty * ty) + (tz * tz));
            var mu = PairFriction(a, b);
            if (speed > 0.0 && mu > 0.0)
            {
                var scale = Math.Min(speed / w, mu * j) / speed;
                ix -= scale * tx;
                iy -= scale * ty;
                iz -= scale * tz;
            }

            v[ia] += wa * ix;
            v[ia + 1] += wa * iy;
            v[ia + 2] += wa * iz;
            v[ib] -= wb * ix;
            v[ib + 1] -= wb * iy;
            v[ib + 2] -= wb * iz;
        }

        return overlap;
    }

    /// <summary>Puts particle i on the surface of obstacle k if it is inside, taking out its approaching normal velocity; returns how far it moved.</summary>
    private double SeparateFromObstacle(in ConstraintContext context, int i, int k, double radius, double time)
    {
        var obstacle = _obstacles[k];
        var x = context.Positions;
        var o = 3 * i;
        var offset = obstacle.OffsetAt(time);
        var gap = obstacle.Distance(x[o] - offset.X, x[o + 1] - offset.Y, x[o + 2] - offset.Z, out var nx, out var ny, out var nz) - radius;
        if (!(gap < 0.0))
        {
            return 0.0;
        }

        x[o] -= gap * nx;
        x[o + 1] -= gap * ny;
        x[o + 2] -= gap * nz;
        var v = context.Velocities;
        var velocity = obstacle.Velocity;
        double rx = v[o] - velocity.X, ry = v[o + 1] - velocity.Y, rz = v[o + 2] - velocity.Z;
        var un = (rx * nx) + (ry * ny) + (rz * nz);
        if (un < 0.0)
        {
            double dx = -un * nx, dy = -un * ny, dz = -un * nz;
            double tx = rx - (un * nx), ty = ry - (un * ny), tz = rz - (un * nz);
            var speed = Math.Sqrt((tx * tx) + (ty * ty) + (tz * tz));
            var mu = FrictionWith(obstacle, i);
            if (speed > 0.0 && mu > 0.0)
            {
                var scale = Math.Min(speed, mu * -un) / speed;
                dx -= scale * tx;
                dy -= scale * ty;
                dz -= scale * tz;
            }

            v[o] += dx;
            v[o + 1] += dy;
            v[o + 2] += dz;
            React(in context, i, k, new Vector3d(dx, dy, dz), new Vector3d(x[o], x[o + 1], x[o + 2]), new Vector3d(nx, ny, nz), time);
        }

        return -gap;
    }
}
