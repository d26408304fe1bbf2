using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Contacts;

/// <summary>
/// Stage 3 of <see cref="ContactSet.Resolve"/>: the impacts within the step, in time order, each changing the rest of its
/// particles' paths (<see cref="ContactSearch"/> finds them, <see cref="ImpactQueue"/> orders them).
/// </summary>
public sealed partial class ContactSet
{
    /// <summary>The most impacts one particle or pair may have in a step on average before the rest is left to the projection.</summary>
    private const int ImpactsPerItem = 16;

    /// <summary>
    /// How near, as a fraction of the radius (or of the sum of two radii), a slow contact at the start of a step counts
    /// as resting: 1e-3, far below the 1 % overlap the contract allows.
    /// </summary>
    private const double RestingMargin = 1e-3;

    /// <summary>
    /// Queues each particle's first obstacle impact and each candidate pair's first impact; then, earliest first,
    /// resolves an impact, changes its particles' paths from then on, and queues their next impacts. Bounded: at most
    /// <see cref="ImpactsPerItem"/> (N + pairs) impacts. The queue holds at most that many and N + pairs more at once,
    /// and grows only to what is queued at once (<see cref="ImpactQueue"/>).
    /// </summary>
    private void ResolveImpacts(in ConstraintContext context)
    {
        var n = context.Count;
        var inverseMasses = context.InverseMasses.ForReading();
        var radii = context.Radii.ForReading();
        var pairs = _pairs.Count;
        var budget = (long)ImpactsPerItem * (n + (long)pairs);
        _queue.Reset((int)Math.Min(budget + n + pairs + 64, int.MaxValue));
        if (_obstacles.Count == 0 && pairs == 0)
        {
            return;
        }

        SettleRestingContacts(in context);
        for (var i = 0; i < n; i++)
        {
            if (inverseMasses[i] != 0.0)
            {
                QueueObstacleImpact(in context, i, 0.0, radii);
            }
        }

        for (var p = 0; p < pairs; p++)
        {
            if (!_pairs.IsResting(p))
            {
                QueuePairImpact(in context, p, 0.0, radii);
            }
        }

        var resolved = 0L;
        while (_queue.Count > 0 && resolved < budget)
        {
            var s = _queue.Pop(out var first, out var second, out var firstEpoch, out var secondEpoch);
            if (second < 0)
            {
                var i = first;
                if (_paths.Version(i) != firstEpoch)
                {
                    continue; // its path changed since: a newer entry is queued
                }

                resolved++;
                if (ResolveObstacleImpact(in context, i, -1 - second, s))
                {
                    Requeue(in context, i, s, radii);
                }
                else
                {
                    QueueObstacleImpact(in context, i, s, radii); // it rests there: its next obstacle, if any
                }
            }
            else
            {
                var a = _pairs.First[first];
                var b = _pairs.Second[first];
                if (_paths.Version(a) != firstEpoch || _paths.Version(b) != secondEpoch || _pairs.IsResting(first))
                {
                    continue;
                }

                resolved++;
                if (ResolvePairImpact(in context, first, s))
                {
                    Requeue(in context, a, s, radii);
                    Requeue(in context, b, s, radii);
                }
            }
        }
    }

    /// <summary>
    /// The contacts that already rest at the start of the step (a particle on the ground, the particles of a pile):
    /// touching, or within <see cref="RestingMargin"/> of the sum of the radii, and meeting at a normal speed u &gt;= 0
    /// whose rebound e u is below <see cref="RestingSpeed"/>. They are resolved at s = 0, before any impact is queued,
    /// exactly as the queue would resolve them first; this spares the queue the thousands of zero-time impacts of a pile.
    /// </summary>
    private void SettleRestingContacts(in ConstraintContext context)
    {
        var n = context.Count;
        var inverseMasses = context.InverseMasses.ForReading();
        var radii = context.Radii.ForReading();
        var x = context.StartPositions.ForReading();
        var v = context.StartVelocities.ForReading();
        for (var i = 0; i < n && _obstacles.Count > 0; i++)
        {
            if (inverseMasses[i] == 0.0)
            {
                continue;
            }

            var radius = Radius(radii, i);
            var candidates = ObstaclesNear(i, Read(x, i), TouchReach(radius), -1);
            for (var c = 0; c < candidates; c++)
            {
                var k = _candidates[c];
                var obstacle = _obstacles[k];
                var q = Read(x, i) - obstacle.OffsetAt(context.Time);
                var gap = obstacle.Distance(q.X, q.Y, q.Z, out var nx, out var ny, out var nz) - radius;
                var u = -Vector3d.Dot(Read(v, i) - obstacle.Velocity, new Vector3d(nx, ny, nz));
                if (gap <= ContactSearch.ToleranceAt(Math.Abs(q.X) + Math.Abs(q.Y) + Math.Abs(q.Z)) + (RestingMargin * radius)
                    && u >= 0.0 && !(RestitutionWith(obstacle, i) * u > _restingSpeed))
                {
                    _ = ResolveObstacleImpact(in context, i, k, 0.0);
                }
            }
        }

        var first = _pairs.First;
        var second = _pairs.Second;
        for (var p = 0; p < first.Length; p++)
        {
            var a = first[p];
            var b = second[p];
            var reach = Radius(radii, a) + Radius(radii, b);
            _paths.Evaluate(a, 0.0, out var pa, out var va);
            _paths.Evaluate(b, 0.0, out var pb, out var vb);
            var d = pa - pb;
            var gap = PairNormal.Of(d.X, d.Y, d.Z, a, b, out var nx, out var ny, out var nz) - reach;
            var u = -Vector3d.Dot(va - vb, new Vector3d(nx, ny, nz));
            if (gap <= ContactSearch.ToleranceAt(Math.Abs(pa.X) + Math.Abs(pa.Y) + Math.Abs(pa.Z)) + (RestingMargin * reach)
                && u >= 0.0 && !(PairRestitution(a, b) * u > _restingSpeed))
            {
                _ = ResolvePairImpact(in context, p, 0.0);
            }
        }
    }

    /// <summary>After particle <paramref name="i"/>'s path changed at <paramref name="s"/>: its next obstacle impact and its pairs' next impacts.</summary>
    private void Requeue(in ConstraintContext context, int i, double s, Span<double> radii)
    {
        if (context.InverseMasses.ForReading()[i] != 0.0)
        {
            QueueObstacleImpact(in context, i, s, radii);
        }

        for (var k = _pairs.StartOf(i); k < _pairs.StartOf(i + 1); k++)
        {
            // A pair that rested at its last contact rests no longer once a bounce changed i's course: a ball hit in
            // a row of touching balls must pass the blow on (Newton's cradle), not have it absorbed by the separation.
            var p = _pairs.PairAt(k);
            _pairs.ClearResting(p);
            QueuePairImpact(in context, p, s, radii);
        }
    }

    private void QueueObstacleImpact(in ConstraintContext context, int i, double from, Span<double> radii)
    {
        var best = double.PositiveInfinity;
        var which = -1;
        var radius = Radius(radii, i);

        // The path from here to the end of the step stays within its chord's box grown by A L^2 / 8 (a cubic departs
        // from its chord by at most that, A bounding |p''| over the stretch of length L): the obstacles out of that box
        // grown by the radius cannot be touched.
        var to = context.Dt;
        _paths.Evaluate(i, from, out var a, out _);
        _paths.Evaluate(i, to, out var b, out _);
        var bulge = 0.125 * _paths.AccelerationBound(i, from, to) * (to - from) * (to - from);
        var lo = new Vector3d(Math.Min(a.X, b.X), Math.Min(a.Y, b.Y), Math.Min(a.Z, b.Z));
        var hi = new Vector3d(Math.Max(a.X, b.X), Math.Max(a.Y, b.Y), Math.Max(a.Z, b.Z));
        var candidates = ObstaclesNear(i, lo, hi, TouchReach(radius) + bulge, -1);
        for (var c = 0; c < candidates; c++)
        {
            var k = _candidates[c];
            if (_resting.IsRestingOn(i, k))
            {
                continue; // it rests there: the resting stage holds it
            }

            var s = ContactSearch.FirstObstacleContact(_paths, i, radius, _obstacles[k], context.Time, from, context.Dt);
            if (s < best)
            {
                best = s;
                which = k;
            }
        }

        if (which >= 0)
        {
            _queue.Push(best, i, -1 - which, _paths.Version(i), 0);
        }
    }

    private void QueuePairImpact(in ConstraintContext context, int p, double from, Span<double> radii)
    {
        var a = _pairs.First[p];
        var b = _pairs.Second[p];
        var s = ContactSearch.FirstPairContact(_paths, a, b, Radius(radii, a) + Radius(radii, b), from, context.Dt);
        if (s <= context.Dt)
        {
            _queue.Push(s, p, 0, _paths.Version(a), _paths.Version(b));
        }
    }

    /// <summary>
    /// Particle i meets obstacle k at s with relative velocity r = v - V: with u = -r . n &gt; 0 the impulse per unit
    /// mass is (1 + e) u n, and friction takes min(|r_t|, mu (1 + e) u) off the tangential r_t. A rebound e u below
    /// <see cref="RestingSpeed"/> is taken as e = 0, and the particle rests on k for the rest of the step.
    /// </summary>
    /// <returns>True for a bounce, which changes the particle's course: its queued impacts are then stale. A resting
    /// impact changes it by less than <see cref="RestingSpeed"/>, and what was queued stands.</returns>
    private bool ResolveObstacleImpact(in ConstraintContext context, int i, int k, double s)
    {
        var obstacle = _obstacles[k];
        _paths.Evaluate(i, s, out var p, out var v);
        var q = p - obstacle.OffsetAt(context.Time + s);
        _ = obstacle.Distance(q.X, q.Y, q.Z, out var nx, out var ny, out var nz);
        var normal = new Vector3d(nx, ny, nz);
        var relative = v - obstacle.Velocity;
        var u = -Vector3d.Dot(relative, normal);
        var restitution = RestitutionWith(obstacle, i);
        var resting = !(restitution * u > _restingSpeed);
        var e = resting ? 0.0 : restitution;
        var dv = Vector3d.Zero;
        var tangent = relative + (u * normal);
        if (u > 0.0)
        {
            dv = (1.0 + e) * u * normal;
            var speed = tangent.Length;
            if (speed > 0.0)
            {
                var cut = Math.Min(speed, FrictionWith(obstacle, i) * (1.0 + e) * u);
                dv -= (cut / speed) * tangent;
                tangent = (1.0 - (cut / speed)) * tangent;
            }
        }

        Kick(in context, i, s, dv, bounce: !resting);
        React(in context, i, k, dv, p, normal, context.Time + s);
        if (resting)
        {
            _resting.Rest(i, k, s, tangent, q);
        }

        _log.Record(context.Time + s, i, k, true, Math.Max(u, 0.0), resting);
        return !resting;
    }

    /// <summary>
    /// Particles a and b meet at s: n = (x_a - x_b) / |x_a - x_b|, u = -(v_a - v_b) . n. The impulse
    /// J = (1 + e) u / (w_a + w_b) along n (w = 1 / m) gives v_a += J w_a n, v_b -= J w_b n: momentum is conserved and
    /// the normal relative velocity becomes e u. Friction: a tangential impulse of at most mu J, which takes
    /// min(|r_t|, mu (1 + e) u) off the relative tangential velocity r_t.
    /// </summary>
    /// <returns>True for a bounce (see <see cref="ResolveObstacleImpact"/>).</returns>
    private bool ResolvePairImpact(in ConstraintContext context, int pair, double s)
    {
        var a = _pairs.First[pair];
        var b = _pairs.Second[pair];
        var inverseMasses = context.InverseMasses.ForReading();
        var wa = inverseMasses[a];
        var wb = inverseMasses[b];
        _paths.Evaluate(a, s, out var pa, out var va);
        _paths.Evaluate(b, s, out var pb, out var vb);
        var d = pa - pb;
        _ = PairNormal.Of(d.X, d.Y, d.Z, a, b, out var nx, out var ny, out var nz);
        var normal = new Vector3d(nx, ny, nz);
        var relative = va - vb;
        var u = -Vector3d.Dot(relative, normal);
        var restitution = PairRestitution(a, b);
        var resting = !(restitution * u > _restingSpeed);
        var e = resting ? 0.0 : restitution;
        if (u > 0.0)
        {
            var j = (1.0 + e) * u / (wa + wb);
            var impulse = j * normal;
            var tangent = relative + (u * normal);
            var speed = tangent.Length;
            if (speed > 0.0)
            {
                var jt = Math.Min(speed / (wa + wb), PairFriction(a, b) * j);
                impulse -= (jt / speed) * tangent;
            }

            Kick(in context, a, s, wa * impulse, bounce: !resting);
            Kick(in context, b, s, -wb * impulse, bounce: !resting);
        }

        if (resting)
        {
            _pairs.MarkResting(pair);
        }

        _log.Record(context.Time + s, a, b, false, Math.Max(u, 0.0), resting);
        return !resting;
    }

    /// <summary>
    /// Adds <paramref name="dv"/> to particle i's velocity from time s on: its path, end position and end velocity; a
    /// bounce also makes its queued impacts stale.
    /// </summary>
    private void Kick(in ConstraintContext context, int i, double s, Vector3d dv, bool bounce)
    {
        if (bounce)
        {
            _paths.Bounce(i);
        }

        if (dv == Vector3d.Zero)
        {
            return;
        }

        _paths.AddVelocity(i, s, dv);
        var rest = context.Dt - s;
        var x = context.Positions;
        var v = context.Velocities;
        x[3 * i] += dv.X * rest;
        x[(3 * i) + 1] += dv.Y * rest;
        x[(3 * i) + 2] += dv.Z * rest;
        v[3 * i] += dv.X;
        v[(3 * i) + 1] += dv.Y;
        v[(3 * i) + 2] += dv.Z;
    }
}
