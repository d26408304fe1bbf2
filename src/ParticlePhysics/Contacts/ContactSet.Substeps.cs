using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Contacts;

/// <summary>
/// The contact set inside the position-based integrator's substeps, after Macklin et al.'s "Small Steps" and Müller et
/// al.'s "Detailed Rigid Body Simulation with XPBD": contacts are inequality constraints of zero compliance.
/// </summary>
/// <remarks>
/// <para>
/// <see cref="Project"/>, once per substep of length h after the prediction: a particle whose predicted move from
/// outside touched the obstacle grown by its radius (found by the same safe steps along the straight move relative to
/// the obstacle, so that nothing tunnels) is held by the tangent plane where it touched, which moves on with the
/// obstacle: touched at s, C = (x - x_touch - V (h - s)) . n &gt;= 0; one that was already inside moves by -C n with
/// C = phi(x) - r and n the gradient. Static friction: if the tangential move relative to the obstacle is shorter than
/// mu times the normal correction, it is undone. Two overlapping particles are pushed apart along their line of
/// centres, each by its share w_i / (w_a + w_b) of the overlap. A pair one of which moved at least its radius in the
/// substep is swept: if their straight moves touched, they are held at the plane of that touch instead, so that
/// particles never pass through each other however fast they close. Each contact is projected once per substep, and a
/// resting stack sinks by g h^2 a layer in each prediction, so its overlaps are a few g h^2: more substeps shrink them
/// as h^2 (for small particles at low frame rates they can pass 1 % of the radius; the force-based stage's separation
/// passes do not have this limit).
/// </para>
/// <para>
/// <see cref="SolveVelocities"/>, after the velocities are taken from the change of positions: dynamic friction takes
/// min(mu |C| / h, |v_t|) off the relative tangential velocity, and the normal relative velocity becomes -e v_n, v_n
/// being the normal velocity before the solve (that of the prediction); 0 when e |v_n| is below
/// <see cref="RestingSpeed"/>, and 0 when it was not approaching.
/// </para>
/// <para>
/// What the two calls expect of the context, as the xpbd integrator makes it: in <see cref="Project"/>, the start is
/// the substep's start (x_prev, v_prev), the positions and velocities are the prediction's (x_prev + h v, v); in
/// <see cref="SolveVelocities"/>, the velocities are (x - x_prev) / h. Both must be called for every substep, in that
/// order: the velocity pass uses the contacts the position pass found. Pass the radii (the world's
/// <see cref="ParticleWorld.Radii"/>): a context without them makes every particle a point.
/// </para>
/// </remarks>
public sealed partial class ContactSet
{
    /// <inheritdoc />
    public void Project(in ConstraintContext context)
    {
        var n = context.Count;
        EnsureCapacity(n);
        _substep.Clear();
        _log.Clear(); // this substep's contacts and pairs, none when collisions are off (not those of an earlier step)
        var x = context.Positions;
        var v = context.Velocities;
        var previous = context.StartPositions.ForReading();
        var inverseMasses = context.InverseMasses.ForReading();
        var radii = context.Radii.ForReading();
        var h = context.Dt;
        var end = context.Time + h;
        _substep.End = end;
        if (!_bracketed)
        {
            _reactions.Clear(_obstacles.Count);
        }

        UpdateObstacleBoxes(context.Time, end);
        if (ParticleCollisions)
        {
            var swept = MarkFastParticles(n, x, previous, radii);
            var pairs = FindRestingPairs(n, x, previous, radii, swept, StillParticles(in context));
            _log.CandidatePairs = pairs;
            var first = _restingGrid.First.ForReading();
            var second = _restingGrid.Second.ForReading();
            for (var p = 0; p < pairs; p++)
            {
                var a = first[p];
                var b = second[p];
                if (context.Sleeping is { } sleeping)
                {
                    WakeOnImpact(in context, sleeping, a, b, radii, swept && (_boxes.Fast[a] || _boxes.Fast[b]));
                }

                var depth = swept && (_boxes.Fast[a] || _boxes.Fast[b])
                    ? SeparateSweptPositions(in context, a, b, radii, out var normal)
                    : SeparatePositions(in context, a, b, radii, out normal);
                if (depth > 0.0)
                {
                    AddSubstepContact(-1, a, b, normal, depth, Vector3d.Dot(Read(v, a) - Read(v, b), normal));
                }
            }
        }

        if (_obstacles.Count == 0)
        {
            return;
        }

        var wakers = AnyObstacleMoves() ? context.Sleeping : null;
        for (var i = 0; i < n; i++)
        {
            if (inverseMasses[i] == 0.0 && !(wakers is not null && WokenByMovingObstacle(in context, wakers, i, Radius(radii, i), end)))
            {
                continue;
            }

            // The obstacles near its straight move, in index order; a projection moves it, so those after the one that
            // moved it are asked again from its new place (as the loop over every obstacle would meet them).
            var radius = Radius(radii, i);
            var candidates = ObstaclesNear(i, Read(previous, i), Read(x, i), TouchReach(radius), -1);
            for (var c = 0; c < candidates; c++)
            {
                var k = _candidates[c];
                var obstacle = _obstacles[k];
                var position = Read(x, i);
                var start = Read(previous, i);
                var p0 = start - obstacle.OffsetAt(context.Time);
                var known = ReferenceEquals(_farObstacles[i], obstacle);
                var knownPoint = known ? _farPoints[i] : Vector3d.Zero;
                var knownGap = known ? _farGaps[i] : double.NegativeInfinity;
                var far = obstacle.IsFarOutside(p0.X, p0.Y, p0.Z, SkipReach(radius, p0, position - start - (h * obstacle.Velocity)), ref knownPoint, ref knownGap);
                if (knownGap > double.NegativeInfinity)
                {
                    _farObstacles[i] = obstacle;
                    _farPoints[i] = knownPoint;
                    _farGaps[i] = knownGap;
                }

                if (far)
                {
                    continue;
                }

                // The distance at the start is asked once, for whether it came from outside and as the search's first
                // step; the end's only when that search does not decide the constraint.
                var startGap = obstacle.Distance(p0.X, p0.Y, p0.Z, out var sx, out var sy, out var sz) - radius;
                var startNormal = new Vector3d(sx, sy, sz);
                var startedOutside = startGap >= 0.0;
                var gap = 0.0;
                var normal = Vector3d.Zero;
                if (!startedOutside)
                {
                    gap = EndGap(obstacle, position, end, radius, out normal);
                }

                if (startedOutside || !(gap < 0.0))
                {
                    // It came from outside: the constraint is the tangent plane where its straight move touched (a thin
                    // wall crossed, or entered deeper than its middle, would otherwise push it out the far side). The
                    // plane moves with the obstacle: touched at s, it is at touch + V (h - s) at the substep's end, so
                    // a moving obstacle carries a particle it met instead of leaving it where they touched.
                    if (Crossed(obstacle, start, position, radius, context.Time, h, startGap, startNormal, out var touch, out var entry))
                    {
                        normal = entry;
                        gap = Vector3d.Dot(position - touch, normal);
                    }
                    else if (startedOutside)
                    {
                        gap = EndGap(obstacle, position, end, radius, out normal);
                    }

                    if (!(gap < 0.0))
                    {
                        continue;
                    }
                }

                position -= gap * normal;
                var depth = -gap;

                // Static friction: undo the tangential move relative to the obstacle when it is within mu |C| (a
                // grain's, of its contact point, by its move and its spin).
                if (_anyGrains && IsGrain(i))
                {
                    position = StickGrain(i, position, Read(previous, i), obstacle, normal, depth, inverseMasses[i], radius, h);
                }
                else
                {
                    var move = position - Read(previous, i) - (h * obstacle.Velocity);
                    var tangential = move - (Vector3d.Dot(move, normal) * normal);
                    if (tangential.Length < FrictionWith(obstacle, i) * depth)
                    {
                        position -= tangential;
                    }
                }

                // The velocity the integrator takes from the positions changes by this push over h: an impulse m dx / h.
                React(in context, i, k, (position - Read(x, i)) / h, position, normal, end);
                Write(x, i, position);
                AddSubstepContact(k, i, -1, normal, depth, Vector3d.Dot(Read(v, i) - obstacle.Velocity, normal));
                candidates = ObstaclesNear(i, Read(previous, i), position, TouchReach(radius), k);
                c = -1;
            }
        }
    }

    /// <inheritdoc />
    public void SolveVelocities(in ConstraintContext context)
    {
        var v = context.Velocities;
        var inverseMasses = context.InverseMasses.ForReading();
        var h = context.Dt;
        var radii = context.Radii.ForReading();
        CountContacts(_substep.Count);
        for (var c = 0; c < _substep.Count; c++)
        {
            var k = _substep.Kind(c);
            var normal = _substep.Normal(c);
            var a = _substep.First(c);
            double e, mu, wa, wb;
            Vector3d relative;
            if (k >= 0)
            {
                var obstacle = _obstacles[k];
                e = RestitutionWith(obstacle, a);
                mu = FrictionWith(obstacle, a);
                wa = 1.0;
                wb = 0.0;
                relative = Read(v, a) - obstacle.Velocity;
            }
            else
            {
                e = PairRestitution(a, _substep.Second(c));
                mu = PairFriction(a, _substep.Second(c));
                wa = inverseMasses[a];
                wb = inverseMasses[_substep.Second(c)];
                relative = Read(v, a) - Read(v, _substep.Second(c));
            }

            var w = wa + wb;
            if (w == 0.0)
            {
                continue;
            }

            // The change of relative velocity, shared out as impulse / mass.
            var vn = Vector3d.Dot(relative, normal);
            var change = Vector3d.Zero;
            var b = k < 0 ? _substep.Second(c) : -1;
            if (_anyGrains && (IsGrain(a) || (b >= 0 && IsGrain(b))))
            {
                var rolling = k >= 0 ? (IsGrain(a) ? _rolling[a] : 0.0) : PairRolling(a, b);
                var p = SolveGrainFriction(a, b, relative, normal, mu, _substep.Depth(c) / (h * w), wa, wb, Radius(radii, a), b >= 0 ? Radius(radii, b) : 0.0, rolling);
                change += w * p;
            }
            else
            {
                var tangent = relative - (vn * normal);
                var speed = tangent.Length;
                if (speed > 0.0)
                {
                    change -= (Math.Min(mu * _substep.Depth(c) / h, speed) / speed) * tangent;
                }
            }

            var approach = _substep.Approach(c);
            var rebound = approach < 0.0 && e * -approach > _restingSpeed ? -e * approach : 0.0;
            change += (rebound - vn) * normal;
            Write(v, a, Read(v, a) + ((wa / w) * change));
            if (k >= 0)
            {
                React(in context, a, k, change, Read(context.Positions, a), normal, context.Time + h);
            }

            if (k < 0)
            {
                Write(v, b, Read(v, b) - ((wb / w) * change));
            }
        }
    }

    /// <summary>Pushes two overlapping particles apart by their shares of the overlap; returns it (0 if none) and the normal.</summary>
    private static double SeparatePositions(in ConstraintContext context, int a, int b, Span<double> radii, out Vector3d normal)
    {
        var inverseMasses = context.InverseMasses.ForReading();
        var wa = inverseMasses[a];
        var wb = inverseMasses[b];
        var x = context.Positions;
        var d = Read(x, a) - Read(x, b);
        var distance = PairNormal.Of(d.X, d.Y, d.Z, a, b, out var nx, out var ny, out var nz);
        normal = new Vector3d(nx, ny, nz);
        var overlap = Radius(radii, a) + Radius(radii, b) - distance;
        if (!(overlap > 0.0) || wa + wb == 0.0)
        {
            return 0.0;
        }

        Write(x, a, Read(x, a) + ((overlap * wa / (wa + wb)) * normal));
        Write(x, b, Read(x, b) - ((overlap * wb / (wa + wb)) * normal));
        return overlap;
    }

    /// <summary>
    /// Marks the particles whose straight move over the substep is at least their radius (any move, for a point); true
    /// if there is one. Two particles whose moves are both shorter than their radii move by less than r_a + r_b
    /// relative to each other, so they cannot cross: from apart, they end apart or overlapping on the side they came
    /// from, which the projection at the end handles. Only a pair with a fast particle needs its moves swept.
    /// </summary>
    private bool MarkFastParticles(int n, Span<double> x, Span<double> previous, Span<double> radii)
    {
        var any = false;
        for (var i = 0; i < n; i++)
        {
            var dx = x[3 * i] - previous[3 * i];
            var dy = x[(3 * i) + 1] - previous[(3 * i) + 1];
            var dz = x[(3 * i) + 2] - previous[(3 * i) + 2];
            var squared = (dx * dx) + (dy * dy) + (dz * dz);
            var radius = Radius(radii, i);
            var fast = squared > 0.0 && !(squared < radius * radius);
            _boxes.Fast[i] = fast;
            any |= fast;
        }

        return any;
    }

    /// <summary>
    /// A pair with a fast particle (<see cref="MarkFastParticles"/>), after Crossed for the obstacles: seen from b, the
    /// straight moves are d(t) = d0 + t (d1 - d0), t in [0, 1] over the substep. Started apart (|d0| &gt;= R), the first
    /// t with |d(t)| = R, the smaller root of A t^2 + 2 B t + (|d0|^2 - R^2) = 0 (A = |d1 - d0|^2, B = d0 . (d1 - d0)
    /// &lt; 0), is where they touched, and the constraint is the plane of that contact, C = d1 . n - R &gt;= 0 with
    /// n = d(t) / R: a pair that crossed is pushed back to the side it came from, where the end's line of centres would
    /// push it on through. Started overlapping, or never within reach, it is projected as <see cref="SeparatePositions"/> does.
    /// </summary>
    private static double SeparateSweptPositions(in ConstraintContext context, int a, int b, Span<double> radii, out Vector3d normal)
    {
        var previous = context.StartPositions.ForReading();
        var x = context.Positions;
        var reach = Radius(radii, a) + Radius(radii, b);
        var d0 = Read(previous, a) - Read(previous, b);
        var d1 = Read(x, a) - Read(x, b);
        var move = d1 - d0;
        var apart = Vector3d.Dot(d0, d0) - (reach * reach);
        var closing = Vector3d.Dot(d0, move);
        var discriminant = (closing * closing) - (Vector3d.Dot(move, move) * apart);
        if (!(reach > 0.0) || !(apart >= 0.0) || !(closing < 0.0) || !(discriminant >= 0.0))
        {
            return SeparatePositions(in context, a, b, radii, out normal);
        }

        var t = apart / (Math.Sqrt(discriminant) - closing); // the smaller root, without cancellation
        if (!(t <= 1.0))
        {
            return SeparatePositions(in context, a, b, radii, out normal); // they touch only after the substep
        }

        var contact = d0 + (t * move);
        _ = PairNormal.Of(contact.X, contact.Y, contact.Z, a, b, out var nx, out var ny, out var nz);
        normal = new Vector3d(nx, ny, nz);
        var inverseMasses = context.InverseMasses.ForReading();
        var wa = inverseMasses[a];
        var wb = inverseMasses[b];
        var overlap = reach - Vector3d.Dot(d1, normal);
        if (!(overlap > 0.0) || wa + wb == 0.0)
        {
            return 0.0;
        }

        Write(x, a, Read(x, a) + ((overlap * wa / (wa + wb)) * normal));
        Write(x, b, Read(x, b) - ((overlap * wb / (wa + wb)) * normal));
        return overlap;
    }

    /// <summary>
    /// Whether the straight move from <paramref name="start"/> to <paramref name="end"/> over the substep touches the
    /// obstacle: then where the centre is at the substep's end on the tangent plane it touched, carried along with the
    /// obstacle since (the touching centre at s plus V (h - s)), and the normal there.
    /// </summary>
    private static bool Crossed(
        Obstacle obstacle,
        Vector3d start,
        Vector3d end,
        double radius,
        double time,
        double h,
        double startGap,
        Vector3d startNormal,
        out Vector3d touch,
        out Vector3d normal)
    {
        touch = start;
        normal = Vector3d.Zero;
        var velocity = ((end - start) / h) - obstacle.Velocity;
        var s = 0.0;
        for (var iteration = 0; iteration < ContactSearch.MaxIterations; iteration++)
        {
            var p = start + (s * (velocity + obstacle.Velocity));
            var q = p - obstacle.OffsetAt(time + s);
            double gap, nx, ny, nz;
            if (iteration == 0)
            {
                // q is the start, where the caller asked already.
                gap = startGap;
                (nx, ny, nz) = (startNormal.X, startNormal.Y, startNormal.Z);
            }
            else
            {
                gap = obstacle.Distance(q.X, q.Y, q.Z, out nx, out ny, out nz) - radius;
            }

            var rate = (velocity.X * nx) + (velocity.Y * ny) + (velocity.Z * nz);
            if (gap <= ContactSearch.ToleranceAt(Math.Abs(q.X) + Math.Abs(q.Y) + Math.Abs(q.Z)) && rate < 0.0)
            {
                touch = p + ((h - s) * obstacle.Velocity);
                normal = new Vector3d(nx, ny, nz);
                return s < h;
            }

            s += obstacle.SafeStep(q.X, q.Y, q.Z, velocity.X, velocity.Y, velocity.Z, radius, gap, rate, 0.0, h - s);
            if (!(s < h))
            {
                return false;
            }
        }

        return false;
    }

    /// <summary>
    /// How far outside the obstacle a particle must start to be skipped: phi is 1-Lipschitz, so along a move of length
    /// |m| relative to it the gap stays above phi(start) - r - |m|, which a margin far above the contact search's
    /// tolerance and the rounding of the moves keeps positive: from there Crossed finds no touch and the end is not
    /// inside, and the loop would go on to the next obstacle.
    /// </summary>
    private static double SkipReach(double radius, Vector3d start, Vector3d move)
    {
        var length = move.Length;
        return radius + length + 1e-6 + (1e-12 * (Math.Abs(start.X) + Math.Abs(start.Y) + Math.Abs(start.Z) + length));
    }

    /// <summary>The gap at the substep's end (phi - r at the end position relative to the obstacle) and the normal there.</summary>
    private static double EndGap(Obstacle obstacle, Vector3d position, double end, double radius, out Vector3d normal)
    {
        var q = position - obstacle.OffsetAt(end);
        var gap = obstacle.Distance(q.X, q.Y, q.Z, out var nx, out var ny, out var nz) - radius;
        normal = new Vector3d(nx, ny, nz);
        return gap;
    }

    private void AddSubstepContact(int kind, int first, int second, Vector3d normal, double depth, double approach)
    {
        // The log of impacts: under substeps, those of the last substep (its end as their time), approaching or resting.
        var e = kind >= 0 ? RestitutionWith(_obstacles[kind], first) : PairRestitution(first, second);
        var u = Math.Max(-approach, 0.0);
        _log.Record(_substep.End, first, kind >= 0 ? kind : second, kind >= 0, u, !(e * u > _restingSpeed));
        _substep.Add(kind, first, second, normal, depth, approach);
    }

    /// <summary>
    /// The pairs whose spheres, grown by a quarter of their radius, overlap at the end positions; with
    /// <paramref name="swept"/>, a particle marked fast has a box over its whole straight move from
    /// <paramref name="previous"/> (a slow one moved less than its radius, which the quarter radius more covers).
    /// </summary>
    private int FindRestingPairs(int n, Span<double> x, Span<double> previous, Span<double> radii, bool swept, bool[]? still)
    {
        var min = _boxes.Min;
        var max = _boxes.Max;
        for (var i = 0; i < n; i++)
        {
            var grow = 1.25 * Radius(radii, i);
            var fast = swept && _boxes.Fast[i];
            for (var c = 0; c < 3; c++)
            {
                var end = x[(3 * i) + c];
                var start = fast ? previous[(3 * i) + c] : end;
                min[(3 * i) + c] = Math.Min(start, end) - grow;
                max[(3 * i) + c] = Math.Max(start, end) + grow;
            }
        }

        var started = BroadPhaseStart();
        if (!_restingGrid.TryFindPairs(min, max, n, BroadPhaseFilter(), _maxCandidatePairs, still))
        {
            RefuseCandidatePairs(n);
        }

        BroadPhaseEnd(started, _restingGrid.PairCount);

        return _restingGrid.PairCount;
    }
}
