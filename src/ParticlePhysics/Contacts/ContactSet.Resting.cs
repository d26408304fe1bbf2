using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Contacts;

/// <summary>Stages 4 and 5 of <see cref="ContactSet.Resolve"/>: resting contact with friction, then separation.</summary>
public sealed partial class ContactSet
{
    /// <summary>The separation passes stop once none moves anything by more than this, in metres (the contract's bound).</summary>
    private const double SeparationTolerance = 1e-6;

    /// <summary>
    /// Each particle that came to rest on an obstacle at time s stays on its surface for the rest of the step,
    /// tau = T - s: its end position is put back on the surface and its approaching normal velocity taken out; that
    /// normal velocity change dv_n is the normal impulse per unit mass N tau / m, so friction may take mu dv_n of
    /// tangential velocity, spread evenly over tau as the deceleration f = mu dv_n / tau (<see cref="CoulombSlide"/>),
    /// against the direction it slid in when it came to rest, or, at rest, against the whole applied tangential force.
    /// The applied tangential acceleration is the integrator's change of tangential velocity over tau (exact under
    /// constant forces for every integrator), and what the integrator moved since the particle came to rest, relative to
    /// the obstacle, is replaced along friction's line by the frictional motion, so that on a plane under constant forces,
    /// under every integrator, a slide stops after v0^2 / (2 mu g) and a particle on an incline sticks exactly when
    /// tan(theta) &lt;= mu.
    /// </summary>
    private void ApplyRestingFriction(in ConstraintContext context)
    {
        var n = context.Count;
        var x = context.Positions;
        var v = context.Velocities;
        var radii = context.Radii.ForReading();
        var end = context.Time + context.Dt;
        for (var i = 0; i < n; i++)
        {
            var k = _restObstacle[i];
            if (k < 0)
            {
                continue;
            }

            var obstacle = _obstacles[k];
            var position = Read(x, i);
            var q = position - obstacle.OffsetAt(end);
            var gap = obstacle.Distance(q.X, q.Y, q.Z, out var nx, out var ny, out var nz) - Radius(radii, i);
            var normal = new Vector3d(nx, ny, nz);
            var velocity = Read(v, i);
            var relative = velocity - obstacle.Velocity;
            var un = Vector3d.Dot(relative, normal);
            if (!(gap < 0.0) && !(gap <= ContactSearch.Tolerance && un < 0.0))
            {
                continue; // it left the surface within the step: no normal force, no friction
            }

            if (gap < 0.0)
            {
                position -= gap * normal;
            }

            if (un < 0.0)
            {
                velocity -= un * normal;
                relative -= un * normal;
            }

            var tau = context.Dt - _restTime[i];
            var f = obstacle.Friction * Math.Max(-un, 0.0);
            if (f > 0.0 && tau > 0.0)
            {
                // The tangential velocity at the start of the rest and at the end, and the displacement since the
                // particle came to rest (relative to the obstacle), in the end's tangent plane.
                var w0 = _restTangent[i] - (Vector3d.Dot(_restTangent[i], normal) * normal);
                var w1 = relative - (Vector3d.Dot(relative, normal) * normal);
                var moved = position - obstacle.OffsetAt(end) - _restPoint[i];
                moved -= Vector3d.Dot(moved, normal) * normal;
                CoulombSlide.Correction(w0, w1, f / tau, tau, moved, out var dw, out var dx);
                velocity += dw;
                position += dx;
            }

            Write(x, i, position);
            Write(v, i, velocity);
        }
    }

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
        var pairs = _pairCount;
        var first = _pairFirst.AsSpan(0, pairs);
        var second = _pairSecond.AsSpan(0, pairs);
        var touching = CollectObstacleContacts(in context, time);
        for (var pass = 0; pass < iterations; pass++)
        {
            var moved = 0.0;
            for (var p = 0; p < pairs; p++)
            {
                var a = first[p];
                var b = second[p];
                moved = Math.Max(moved, SeparatePair(in context, a, b, inverseMasses[a], inverseMasses[b], radii));
            }

            for (var c = 0; c < touching; c++)
            {
                var i = _nearParticle[c];
                moved = Math.Max(moved, SeparateFromObstacle(in context, i, _nearObstacle[c], Radius(radii, i), time));
            }

            if (moved <= SeparationTolerance)
            {
                pairs = 0; // converged: no shock pass needed
                break;
            }
        }

        if (pairs > 0)
        {
            PropagateShock(in context, pairs, touching, first, second, inverseMasses, radii);
        }

        for (var i = 0; i < n; i++)
        {
            if (inverseMasses[i] != 0.0)
            {
                for (var k = 0; k < _obstacles.Count; k++)
                {
                    _ = SeparateFromObstacle(in context, i, k, Radius(radii, i), time);
                }
            }
        }
    }

    /// <summary>The (particle, obstacle) pairs within a quarter radius (or 1e-6 m) of touching at the end of the step.</summary>
    private int CollectObstacleContacts(in ConstraintContext context, double time)
    {
        var n = context.Count;
        var inverseMasses = context.InverseMasses.ForReading();
        var radii = context.Radii.ForReading();
        var x = context.Positions;
        var count = 0;
        for (var i = 0; i < n && _obstacles.Count > 0; i++)
        {
            if (inverseMasses[i] == 0.0)
            {
                continue;
            }

            var radius = Radius(radii, i);
            for (var k = 0; k < _obstacles.Count; k++)
            {
                var obstacle = _obstacles[k];
                var q = Read(x, i) - obstacle.OffsetAt(time);
                var gap = obstacle.Distance(q.X, q.Y, q.Z, out _, out _, out _) - radius;
                if (gap < (0.25 * radius) + 1e-6)
                {
                    if (count == _nearParticle.Length)
                    {
                        var capacity = Math.Max(64, 2 * count);
                        Array.Resize(ref _nearParticle, capacity);
                        Array.Resize(ref _nearObstacle, capacity);
                    }

                    _nearParticle[count] = i;
                    _nearObstacle[count] = k;
                    count++;
                }
            }
        }

        return count;
    }

    /// <summary>One pass over the pairs in order of rank from the support, the particle nearer it held still.</summary>
    private void PropagateShock(
        in ConstraintContext context, int pairs, int touching, Span<int> first, Span<int> second, Span<double> inverseMasses,
        Span<double> radii)
    {
        var n = context.Count;
        if (_rank.Length < n)
        {
            _rank = new int[n];
            _frontier = new int[n];
            _rankedStart = new int[n + 2];
        }

        if (_rankedPairs.Length < pairs)
        {
            _rankedPairs = new int[Math.Max(pairs, (int)Math.Min(2L * _rankedPairs.Length, DefaultMaxCandidatePairs))];
            _pairsNear = new int[2 * _rankedPairs.Length];
        }

        // Each particle's touching pairs (CSR), then ranks by breadth-first search from the particles on obstacles.
        var x = context.Positions;
        Array.Clear(_rankedStart, 0, n + 2);
        for (var p = 0; p < pairs; p++)
        {
            _rankedStart[first[p] + 2]++;
            _rankedStart[second[p] + 2]++;
        }

        for (var i = 0; i < n; i++)
        {
            _rankedStart[i + 2] += _rankedStart[i + 1];
        }

        for (var p = 0; p < pairs; p++)
        {
            _pairsNear[_rankedStart[first[p] + 1]++] = p;
            _pairsNear[_rankedStart[second[p] + 1]++] = p;
        }

        const int unranked = int.MaxValue;
        var head = 0;
        var tail = 0;
        for (var i = 0; i < n; i++)
        {
            _rank[i] = inverseMasses[i] == 0.0 ? 0 : unranked;
            if (_rank[i] == 0)
            {
                _frontier[tail++] = i;
            }
        }

        for (var c = 0; c < touching; c++)
        {
            var i = _nearParticle[c];
            if (_rank[i] != 0)
            {
                _rank[i] = 0;
                _frontier[tail++] = i;
            }
        }

        while (head < tail)
        {
            var i = _frontier[head++];
            for (var k = _rankedStart[i]; k < _rankedStart[i + 1]; k++)
            {
                var p = _pairsNear[k];
                var j = first[p] == i ? second[p] : first[p];
                if (_rank[j] == unranked && Touching(x, i, j, radii))
                {
                    _rank[j] = _rank[i] + 1;
                    _frontier[tail++] = j;
                }
            }
        }

        // Pairs by the rank of their lower end (a stable counting sort; unranked pairs last, in their own order).
        Array.Clear(_rankedStart, 0, n + 2);
        for (var p = 0; p < pairs; p++)
        {
            _rankedStart[Math.Min(LowerRank(first[p], second[p]), n) + 1]++;
        }

        for (var r = 0; r <= n; r++)
        {
            _rankedStart[r + 1] += _rankedStart[r];
        }

        for (var p = 0; p < pairs; p++)
        {
            _rankedPairs[_rankedStart[Math.Min(LowerRank(first[p], second[p]), n)]++] = p;
        }

        for (var k = 0; k < pairs; k++)
        {
            var p = _rankedPairs[k];
            var a = first[p];
            var b = second[p];
            var wa = inverseMasses[a];
            var wb = inverseMasses[b];
            if (_rank[a] < _rank[b])
            {
                wa = 0.0;
            }
            else if (_rank[b] < _rank[a])
            {
                wb = 0.0;
            }

            _ = SeparatePair(in context, a, b, wa, wb, radii);
        }
    }

    private int LowerRank(int a, int b) => Math.Min(_rank[a], _rank[b]);

    private static bool Touching(Span<double> x, int i, int j, Span<double> radii)
    {
        var dx = x[3 * i] - x[3 * j];
        var dy = x[(3 * i) + 1] - x[(3 * j) + 1];
        var dz = x[(3 * i) + 2] - x[(3 * j) + 2];
        var reach = (1.0 + RestingMargin) * (Radius(radii, i) + Radius(radii, j));
        return (dx * dx) + (dy * dy) + (dz * dz) <= reach * reach;
    }

    /// <summary>
    /// The pairs whose spheres, grown by a quarter of their radius, overlap at the end positions; with
    /// <paramref name="swept"/>, a particle marked fast has a box over its whole straight move from
    /// <paramref name="previous"/> (a slow one moved less than its radius, which the quarter radius more covers).
    /// </summary>
    private int FindRestingPairs(int n, Span<double> x, Span<double> previous, Span<double> radii, bool swept)
    {
        for (var i = 0; i < n; i++)
        {
            var grow = 1.25 * Radius(radii, i);
            var fast = swept && _fast[i];
            for (var c = 0; c < 3; c++)
            {
                var end = x[(3 * i) + c];
                var start = fast ? previous[(3 * i) + c] : end;
                _boxMin[(3 * i) + c] = Math.Min(start, end) - grow;
                _boxMax[(3 * i) + c] = Math.Max(start, end) + grow;
            }
        }

        if (!_restingGrid.TryFindPairs(_boxMin, _boxMax, n, PairFilter, _maxCandidatePairs))
        {
            RefuseCandidatePairs(n);
        }

        return _restingGrid.PairCount;
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
            if (speed > 0.0 && _particleFriction > 0.0)
            {
                var scale = Math.Min(speed / w, _particleFriction * j) / speed;
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
            if (speed > 0.0 && obstacle.Friction > 0.0)
            {
                var scale = Math.Min(speed, obstacle.Friction * -un) / speed;
                dx -= scale * tx;
                dy -= scale * ty;
                dz -= scale * tz;
            }

            v[o] += dx;
            v[o + 1] += dy;
            v[o + 2] += dz;
        }

        return -gap;
    }
}
