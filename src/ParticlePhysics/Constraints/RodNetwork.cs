using System;
using System.Runtime.InteropServices;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Constraints;

/// <summary>
/// Rods and cables between two particles, or between a particle and a fixed anchor. A rod holds its ends at exactly
/// its length L: C = |x_i - x_j| - L = 0 (L from about 5.6e-309 m to 1.34e154 m: its inverse and its square finite).
/// A cable holds them at most L apart (C &lt;= 0): a rod while taut, nothing while slack; going taut is an inelastic
/// impact (the separating velocity is removed by an impulse along the cable).
/// </summary>
/// <remarks>
/// <para>
/// Under the force-based integrators the rods' tension is a constraint force computed at every evaluation (Witkin and
/// Baraff, "Constrained Dynamics"; <see cref="IConstraintForces"/>). With the smooth form C_r = (d . d - L^2) / 2,
/// d = x_i - x_j and e = v_i - v_j, the Jacobian row is (+d at i, -d at j), J' q' = e . e and C' = d . e; requiring
/// C'' = 0 under the applied forces Q gives (J W J^T) lambda = -J' q' - J W Q - ks C - kd C', and the constraint
/// force J^T lambda is lambda d at i and -lambda d at j (W: the inverse masses). The rods then follow the integrator's
/// stages exactly, so each integrator keeps its order; what drifts (the error of the step itself) is removed after the
/// step by <see cref="Resolve"/>: the positions are projected onto C = 0 by Newton's method in the mass metric
/// (dx = W J^T mu with (J W J^T) mu = -C, unit gradients), then the velocities onto C' = 0 (dv = W J^T nu,
/// (J W J^T) nu = -J v), which keeps every length within 1e-12 of L. After a kick and a drift (semi-implicit Euler,
/// <see cref="ConstraintContext.KickDrift"/>) the positions move along the gradients at the step's start instead, and
/// the velocities with them (SHAKE), which keeps the energy bounded where the projection of positions alone let it grow
/// without bound.
/// </para>
/// <para>
/// J W J^T couples two constraints that share a free particle. When the constraints only couple to neighbours a few
/// indices away (a chain added in order: band 1, tridiagonal), it is solved directly by a band Cholesky
/// factorisation; otherwise (a net) by Jacobi-preconditioned conjugate gradients, matrix-free. Both use buffers sized
/// when the topology changes, so an evaluation allocates nothing. A cable is in the solve while it is taut (at or
/// beyond its length and not shortening) and only if it pulls: one that would push is dropped and the system solved
/// again (at most once per cable).
/// </para>
/// <para>
/// Under xpbd (<see cref="Project"/>) each rod is projected once per substep with compliance 0:
/// dlambda = -C / (w_i + w_j), x_i += w_i dlambda u, x_j -= w_j dlambda u (u = d / |d|), in colour order
/// (<see cref="ConstraintColouring"/>); a cable only when it is stretched (C &gt; 0). The velocities taken from the
/// change of positions then carry the inelastic impact of a cable going taut.
/// </para>
/// </remarks>
public sealed class RodNetwork : IStatefulConstraintSet, IConstraintForces, IForceJacobian
{
    /// <summary>The largest half-bandwidth of J W J^T solved by the direct band factorisation; wider ones use conjugate gradients.</summary>
    public const int MaxDirectBandwidth = 16;

    // A cable is taut when its length is at least L (1 - TautTolerance) and it shortens more slowly than
    // TautTolerance L per second.
    private const double TautTolerance = 1e-9;

    // The drift projection stops when every violated length is within this fraction of L, or after MaxNewtonIterations.
    private const double ProjectionTolerance = 1e-13;
    private const int MaxNewtonIterations = 20;

    // Conjugate gradients stop at this relative residual, or after 2 n + 50 iterations (n links).
    private const double SolveTolerance = 1e-13;

    // The second end of a link to a fixed anchor.
    private const int Anchored = -1;

    private readonly ParticleWorld _world;

    // The links: ends (second -1 for an anchor), anchor points (3 per link), lengths, cable flags.
    private int[] _first = Array.Empty<int>();
    private int[] _second = Array.Empty<int>();
    private double[] _anchor = Array.Empty<double>();
    private double[] _length = Array.Empty<double>();
    private bool[] _cable = Array.Empty<bool>();
    private int _count;
    private int _cableCount;

    // Topology, rebuilt when links are added or the world's particle count changes: links by particle, colour order,
    // the band of J W J^T.
    private bool _topologyStale = true;
    private int _particles = -1;
    private int[] _linksStart = Array.Empty<int>();
    private int[] _links = Array.Empty<int>();
    private int[] _order = Array.Empty<int>();
    private int[] _colourStarts = { 0 };
    private int _bandwidth;

    // Per solve: gradients (3 per link), right-hand side, multipliers, active flags, band matrix, CG vectors, and one
    // 3-vector per particle.
    private double[] _gradient = Array.Empty<double>();
    private double[] _rhs = Array.Empty<double>();
    private double[] _lambda = Array.Empty<double>();
    private double[] _tension = Array.Empty<double>();
    private double[] _savedTension = Array.Empty<double>(); // the tensions as they were before a step (BeginStep)
    private int _savedTensionCount;
    private bool[] _active = Array.Empty<bool>();
    private double[] _band = Array.Empty<double>();
    private double[] _residual = Array.Empty<double>();
    private double[] _direction = Array.Empty<double>();
    private double[] _product = Array.Empty<double>();
    private double[] _preconditioned = Array.Empty<double>();
    private double[] _diagonal = Array.Empty<double>();
    private double[] _perParticle = Array.Empty<double>();

    // SHAKE's projection after a kick and a drift: the multipliers of its accepted iterations, and of the last one.
    private double[] _kick = Array.Empty<double>();
    private double[] _kickStep = Array.Empty<double>();

    // The implicit step's linearisation (IForceJacobian): a h^2 times each link's tension per unit length, and the
    // number of links it covers (-1 before the first).
    private double[] _geometric = Array.Empty<double>();
    private int _linearizedLinks = -1;

    private double _driftStiffness;
    private double _driftDamping;

    /// <summary>An empty network for the particles of <paramref name="world"/> (add it with <see cref="ParticleWorld.AddConstraints"/>).</summary>
    public RodNetwork(ParticleWorld world)
    {
        Guard.NotNull(world, nameof(world));
        _world = world;
    }

    /// <summary>The number of rods and cables.</summary>
    public int Count => _count;

    /// <summary>
    /// ks, the feedback on the constraint's value in the constraint forces, in 1/s^2 (default 0): the projection after
    /// each step already removes the drift, so it is only needed by hosts that skip it.
    /// </summary>
    public double DriftStiffness
    {
        get => _driftStiffness;
        set
        {
            _world.ThrowIfStepping();
            Guard.NonNegativeFinite(value, nameof(DriftStiffness));
            _driftStiffness = value;
        }
    }

    /// <summary>kd, the feedback on the constraint's rate of change in the constraint forces, in 1/s (default 0).</summary>
    public double DriftDamping
    {
        get => _driftDamping;
        set
        {
            _world.ThrowIfStepping();
            Guard.NonNegativeFinite(value, nameof(DriftDamping));
            _driftDamping = value;
        }
    }

    /// <summary>True when the solver of J W J^T is the direct band factorisation (a chain), false for conjugate gradients.</summary>
    public bool SolvesDirectly
    {
        get
        {
            EnsureTopology(_world.Count);
            return _bandwidth <= MaxDirectBandwidth;
        }
    }

    /// <summary>Adds a rod of length <paramref name="length"/> between two different existing particles.</summary>
    /// <returns>The index of the new link.</returns>
    public int AddRod(int first, int second, double length) => Add(first, CheckedSecond(second), Vector3d.Zero, length, cable: false);

    /// <summary>Adds a rod of length <paramref name="length"/> between a particle and a fixed anchor point.</summary>
    /// <returns>The index of the new link.</returns>
    public int AddAnchoredRod(int particle, Vector3d anchor, double length) => Add(particle, Anchored, anchor, length, cable: false);

    /// <summary>Adds a cable of length <paramref name="length"/> between two different existing particles.</summary>
    /// <returns>The index of the new link.</returns>
    public int AddCable(int first, int second, double length) => Add(first, CheckedSecond(second), Vector3d.Zero, length, cable: true);

    /// <summary>Adds a cable of length <paramref name="length"/> between a particle and a fixed anchor point.</summary>
    /// <returns>The index of the new link.</returns>
    public int AddAnchoredCable(int particle, Vector3d anchor, double length) => Add(particle, Anchored, anchor, length, cable: true);

    /// <summary>The length L of a link, in metres.</summary>
    public double GetLength(int link)
    {
        CheckLink(link);
        return _length[link];
    }

    /// <summary>The particles a link joins; the second is -1 for a link to a fixed anchor.</summary>
    public (int First, int Second) GetEnds(int link)
    {
        CheckLink(link);
        return (_first[link], _second[link]);
    }

    /// <summary>The fixed anchor point of a link to an anchor (one whose second end <see cref="GetEnds"/> gives as -1).</summary>
    /// <exception cref="ArgumentException">The link joins two particles.</exception>
    public Vector3d GetAnchor(int link)
    {
        CheckLink(link);
        if (_second[link] != Anchored)
        {
            throw new ArgumentException($"link {link} joins particles {_first[link]} and {_second[link]}, not a particle and an anchor.", nameof(link));
        }

        return new Vector3d(_anchor[3 * link], _anchor[(3 * link) + 1], _anchor[(3 * link) + 2]);
    }

    /// <summary>True when the link is a cable, false for a rod.</summary>
    public bool IsCable(int link)
    {
        CheckLink(link);
        return _cable[link];
    }

    /// <summary>
    /// The tension of a link at the last evaluation of the constraint forces, in newtons (positive when it pulls its
    /// ends together; 0 for a slack cable, and before any evaluation).
    /// </summary>
    public double GetTension(int link)
    {
        CheckLink(link);
        return link < _tension.Length ? _tension[link] : 0.0;
    }

    /// <inheritdoc />
    /// <remarks>Keeps the tensions aside (<see cref="GetTension"/> is the last evaluation's, which a failed step ran).</remarks>
    public void BeginStep()
    {
        if (_savedTension.Length < _tension.Length)
        {
            _savedTension = new double[_tension.Length];
        }

        _savedTensionCount = _tension.Length;
        _tension.AsSpan().CopyTo(_savedTension);
    }

    /// <inheritdoc />
    public void CommitStep()
    {
    }

    /// <inheritdoc />
    /// <remarks>
    /// The tensions are those before the step again; links that the step's first evaluation sized for show 0, as
    /// they did before any evaluation.
    /// </remarks>
    public void DiscardStep()
    {
        var kept = Math.Min(_savedTensionCount, _tension.Length);
        _savedTension.AsSpan(0, kept).CopyTo(_tension);
        _tension.AsSpan(kept).Clear();
    }

    /// <summary>
    /// The largest violation over the links for <paramref name="positions"/> (3 values per particle), relative to each
    /// link's length: | |d| - L | / L for a rod, max(0, |d| - L) / L for a cable.
    /// </summary>
    public double MaxRelativeViolation(ReadOnlySpan<double> positions)
    {
        var x = positions.ForReading();
        if (x.Length < 3 * _world.Count)
        {
            throw new ArgumentException(
                $"positions must hold 3 values per particle of the world, {3 * _world.Count}; got {x.Length}.", nameof(positions));
        }

        var worst = 0.0;
        for (var r = 0; r < _count; r++)
        {
            var l = Distance(x, r, out _, out _, out _);
            var violation = (l - _length[r]) / _length[r];
            worst = Math.Max(worst, _cable[r] ? violation : Math.Abs(violation));
        }

        return worst;
    }

    /// <inheritdoc />
    public void AddConstraintForces(in ParticleState state, Span<double> forces)
    {
        if (_count == 0)
        {
            return;
        }

        EnsureTopology(state.Count);
        var x = state.Positions.ForReading();
        var v = state.Velocities.ForReading();
        var w = state.InverseMasses.ForReading();
        for (var r = 0; r < _count; r++)
        {
            int i = 3 * _first[r], j = 3 * _second[r];
            double dx, dy, dz, ex, ey, ez, qx, qy, qz;
            var wi = w[_first[r]];
            if (j >= 0)
            {
                var wj = w[_second[r]];
                dx = x[i] - x[j];
                dy = x[i + 1] - x[j + 1];
                dz = x[i + 2] - x[j + 2];
                ex = v[i] - v[j];
                ey = v[i + 1] - v[j + 1];
                ez = v[i + 2] - v[j + 2];
                qx = (wi * forces[i]) - (wj * forces[j]);
                qy = (wi * forces[i + 1]) - (wj * forces[j + 1]);
                qz = (wi * forces[i + 2]) - (wj * forces[j + 2]);
            }
            else
            {
                var a = 3 * r;
                dx = x[i] - _anchor[a];
                dy = x[i + 1] - _anchor[a + 1];
                dz = x[i + 2] - _anchor[a + 2];
                ex = v[i];
                ey = v[i + 1];
                ez = v[i + 2];
                qx = wi * forces[i];
                qy = wi * forces[i + 1];
                qz = wi * forces[i + 2];
            }

            var squared = (dx * dx) + (dy * dy) + (dz * dz);
            var rate = (dx * ex) + (dy * ey) + (dz * ez);
            var length = _length[r];
            var active = squared > 0.0;
            if (active && _cable[r])
            {
                var l = Math.Sqrt(squared);
                active = l >= length * (1.0 - TautTolerance) && rate / l >= -TautTolerance * length;
            }

            SetGradient(r, dx, dy, dz);
            _active[r] = active;
            var value = 0.5 * (squared - (length * length));
            _rhs[r] = -((ex * ex) + (ey * ey) + (ez * ez)) - ((dx * qx) + (dy * qy) + (dz * qz))
                - (_driftStiffness * value) - (_driftDamping * rate);
        }

        SolveWithPullingCables(w);
        for (var r = 0; r < _count; r++)
        {
            var lambda = _lambda[r];
            var g = 3 * r;
            var length = Math.Sqrt((_gradient[g] * _gradient[g]) + (_gradient[g + 1] * _gradient[g + 1]) + (_gradient[g + 2] * _gradient[g + 2]));
            _tension[r] = -lambda * length;
            if (lambda == 0.0)
            {
                continue;
            }

            int i = 3 * _first[r], j = 3 * _second[r];
            double fx = lambda * _gradient[g], fy = lambda * _gradient[g + 1], fz = lambda * _gradient[g + 2];
            forces[i] += fx;
            forces[i + 1] += fy;
            forces[i + 2] += fz;
            if (j >= 0)
            {
                forces[j] -= fx;
                forces[j + 1] -= fy;
                forces[j + 2] -= fz;
            }
        }
    }

    /// <inheritdoc />
    /// <remarks>
    /// The geometric stiffness of the tensions of the last <see cref="AddConstraintForces"/>, which the world runs at the
    /// same state just before (Tournier et al., "Stable Constrained Dynamics", 2015). The force lambda d on end i
    /// (d = x_i - x_j, lambda &lt; 0 pulling) changes with the ends' positions, at fixed lambda, by
    /// d(lambda d) / dx_i = lambda I: a zero-length spring of stiffness k = -lambda = T / |d|, the tension per unit length.
    /// Why: an implicit step that sees the tension only as a force applies it along the start's direction while the rod
    /// turns, and that does work (on a chain under gravity the step is then semi-implicit Euler's, with its gain: see
    /// ProjectIntoTheKick). With this linearisation the step's tension acts along the end's direction,
    /// lambda_0 (x1_i - x1_j), where the velocities are tangent to the rods to O(h^2): the tension does no work to
    /// leading order, and implicit Euler dissipates |dv|_M^2 / 2 per step, as it does on any force. On a uniform
    /// rotation the step is backward Euler's on y' = i omega y: it turns by atan(h omega) and keeps
    /// 1 / sqrt(1 + (h omega)^2) of the speed. Left out:
    /// the derivatives of lambda itself (J^T dlambda / dx, along the rods, dense over a chain and not symmetric), which
    /// the projection after the step stands in for; and a rod that pushes (lambda &gt; 0), whose positive stiffness
    /// could make the implicit system indefinite, as springs clamp their compressed transverse stiffness. No velocity
    /// derivative: J = a K.
    /// </remarks>
    public void Linearize(
        in ParticleState state, double positionScale, double velocityScale, Span<double> positionJacobianTimesVelocity)
    {
        EnsureTopology(state.Count);
        var v = state.Velocities.ForReading();
        for (var r = 0; r < _count; r++)
        {
            var k = _lambda[r] < 0.0 ? -_lambda[r] : 0.0;
            _geometric[r] = positionScale * k;
            if (k == 0.0)
            {
                continue;
            }

            // (df/dx) v: -k (v_i - v_j) on end i, +k (v_i - v_j) on end j.
            int i = 3 * _first[r], j = 3 * _second[r];
            for (var c = 0; c < 3; c++)
            {
                var relative = j >= 0 ? v[i + c] - v[j + c] : v[i + c];
                positionJacobianTimesVelocity[i + c] -= k * relative;
                if (j >= 0)
                {
                    positionJacobianTimesVelocity[j + c] += k * relative;
                }
            }
        }

        _linearizedLinks = _count;
    }

    /// <inheritdoc />
    /// <exception cref="InvalidOperationException">No <see cref="Linearize"/> yet, or links were added since.</exception>
    public void AddJacobianProduct(ReadOnlySpan<double> w, Span<double> result)
    {
        CheckLinearized();
        var wr = w.ForReading();
        for (var r = 0; r < _count; r++)
        {
            var g = _geometric[r];
            if (g == 0.0)
            {
                continue;
            }

            int i = 3 * _first[r], j = 3 * _second[r];
            for (var c = 0; c < 3; c++)
            {
                var relative = j >= 0 ? wr[i + c] - wr[j + c] : wr[i + c];
                result[i + c] -= g * relative;
                if (j >= 0)
                {
                    result[j + c] += g * relative;
                }
            }
        }
    }

    /// <inheritdoc />
    /// <exception cref="InvalidOperationException">No <see cref="Linearize"/> yet, or links were added since.</exception>
    public void AddDiagonalBlocks(Span<double> blocks)
    {
        CheckLinearized();
        for (var r = 0; r < _count; r++)
        {
            var g = _geometric[r];
            if (g == 0.0)
            {
                continue;
            }

            AddIsotropic(blocks, _first[r], -g);
            if (_second[r] >= 0)
            {
                AddIsotropic(blocks, _second[r], -g);
            }
        }
    }

    /// <inheritdoc />
    /// <remarks>
    /// Removes the drift that the step left: positions onto C = 0 (rods, and cables stretched beyond their length) by
    /// Newton's method in the mass metric, then velocities onto C' = 0 (rods, and taut cables that separate: the
    /// inelastic impulse of a cable going taut).
    /// </remarks>
    public void Resolve(in ConstraintContext context)
    {
        if (_count == 0)
        {
            return;
        }

        EnsureTopology(context.Count);
        var w = context.InverseMasses.ForReading();
        var x = context.Positions;
        if (context.KickDrift)
        {
            ProjectIntoTheKick(context, w);
        }

        // Newton in the mass metric along the current gradients: the whole projection after the other integrators;
        // after a kick and a drift only a check, unless SHAKE's iteration above stopped short of the tolerance.
        for (var iteration = 0; iteration < MaxNewtonIterations; iteration++)
        {
            var worst = 0.0;
            for (var r = 0; r < _count; r++)
            {
                var l = Distance(x, r, out var dx, out var dy, out var dz);
                var violation = l - _length[r];
                var active = l > 0.0 && (!_cable[r] || violation > 0.0);
                _active[r] = active;
                _rhs[r] = -violation;
                if (active)
                {
                    worst = Math.Max(worst, Math.Abs(violation) / _length[r]);
                    SetGradient(r, dx / l, dy / l, dz / l);
                }
                else
                {
                    SetGradient(r, 0, 0, 0);
                }
            }

            if (worst <= ProjectionTolerance)
            {
                break;
            }

            Solve(w);
            ApplyCorrection(w, x);
        }

        var vel = context.Velocities;
        var any = false;
        for (var r = 0; r < _count; r++)
        {
            var l = Distance(x, r, out var dx, out var dy, out var dz);
            var rate = 0.0;
            if (l > 0.0)
            {
                dx /= l;
                dy /= l;
                dz /= l;
                int i = 3 * _first[r], j = 3 * _second[r];
                rate = (dx * vel[i]) + (dy * vel[i + 1]) + (dz * vel[i + 2]);
                if (j >= 0)
                {
                    rate -= (dx * vel[j]) + (dy * vel[j + 1]) + (dz * vel[j + 2]);
                }
            }

            var active = l > 0.0 && (!_cable[r] || (l >= _length[r] * (1.0 - TautTolerance) && rate > 0.0));
            _active[r] = active;
            any |= active;
            SetGradient(r, dx, dy, dz);
            _rhs[r] = -rate;
        }

        if (any)
        {
            SolveWithPullingCables(w);
            ApplyCorrection(w, vel);
        }
    }

    /// <summary>
    /// SHAKE's projection after a kick and a drift (<see cref="ConstraintContext.KickDrift"/>): the end positions move
    /// along the gradients at the step's start, x1 += W J(x0)^T mu with C(x1) = 0, and the end velocities by the same
    /// over dt, so that x1 = x0 + dt v1 still holds. Why, in the smooth form of <see cref="AddConstraintForces"/>
    /// (A = J W J^T, b_r = |e_r|^2 the rods' centripetal terms, lambda the explicit tension, Q the applied forces): the
    /// kick leaves the tangent space, J(x0) v1 = -dt b, and the kick and the drift change the energy by
    /// (dt^2 / 2) (lambda^T A lambda - |Q|_W^2), in which (dt^2 / 2) b^T A^-1 b grows as the fourth power of the
    /// speeds. Moving the positions alone onto the rods leaves that energy in the velocities, so chains run away. The
    /// end lies off the rods by C(x1) = -dt^2 b / 2, so A mu = dt^2 b / 2 to leading order, and with mu folded into the
    /// kick v1 . M dv = (J(x0) v1) . mu / dt = -(dt^2 / 2) b^T A^-1 b takes that back: the step is the constrained
    /// symplectic Euler method (Hairer, Lubich and Wanner, "Geometric Numerical Integration", VII.1),
    /// v1 = v0 + dt W (Q(x0) + J(x0)^T Lambda), x1 = x0 + dt v1, C(x1) = 0, then the velocities projected onto C' = 0
    /// at x1 (RATTLE's second projection, which only removes energy), and its energy stays bounded. On a uniform
    /// rotation it keeps the speed exactly and turns by asin(h omega). The gradients must be the start's: along the
    /// end's, dv would lie along the normals that the velocity projection removes, and change nothing.
    /// mu is found by the quasi-Newton iteration of SHAKE, (J(x0) W J(x0)^T) dmu = -C(x): it contracts as fast as the
    /// rods turn in a step. An iteration that does not shrink the largest violation (a rod that turned by nearly a right
    /// angle, or a state far off its rods) is undone, and the Newton projection along the current gradients finishes
    /// without touching the velocities, as after the other integrators.
    /// </summary>
    private void ProjectIntoTheKick(in ConstraintContext context, Span<double> w)
    {
        var x = context.Positions;
        var x0 = context.StartPositions.ForReading();
        for (var r = 0; r < _count; r++)
        {
            var l0 = Distance(x0, r, out var dx, out var dy, out var dz);
            if (l0 > 0.0)
            {
                SetGradient(r, dx / l0, dy / l0, dz / l0);
            }
            else
            {
                SetGradient(r, 0, 0, 0);
            }

            _kick[r] = 0.0;
        }

        var worst = KickViolations(x);
        var any = false;
        for (var iteration = 0; iteration < MaxNewtonIterations && worst > ProjectionTolerance; iteration++)
        {
            Solve(w);
            for (var r = 0; r < _count; r++)
            {
                _kickStep[r] = _active[r] ? _lambda[r] : 0.0;
            }

            AddStartCorrection(w, x, _kickStep, 1.0);
            var next = KickViolations(x);
            if (!(next < worst))
            {
                AddStartCorrection(w, x, _kickStep, -1.0);
                break;
            }

            for (var r = 0; r < _count; r++)
            {
                _kick[r] += _kickStep[r];
                any |= _kickStep[r] != 0.0;
            }

            worst = next;
        }

        if (any)
        {
            AddStartCorrection(w, context.Velocities, _kick, 1.0 / context.Dt);
        }
    }

    /// <summary>
    /// The violations at <paramref name="x"/> for SHAKE's iteration (the start gradients set): the right-hand side -C,
    /// the active links (a start direction, and a rod, or a cable stretched beyond its length); returns the largest
    /// |C| / L.
    /// </summary>
    private double KickViolations(Span<double> x)
    {
        var worst = 0.0;
        for (var r = 0; r < _count; r++)
        {
            var violation = Distance(x, r, out _, out _, out _) - _length[r];
            var active = GradientDot(r, r) > 0.0 && (!_cable[r] || violation > 0.0);
            _active[r] = active;
            _rhs[r] = -violation;
            if (active)
            {
                worst = Math.Max(worst, Math.Abs(violation) / _length[r]);
            }
        }

        return worst;
    }

    /// <summary>Adds W J^T (scale m) into <paramref name="target"/> for every link with m_r != 0 (J's rows the gradients set).</summary>
    private void AddStartCorrection(Span<double> w, Span<double> target, double[] multipliers, double scale)
    {
        for (var r = 0; r < _count; r++)
        {
            var m = multipliers[r];
            if (m == 0.0)
            {
                continue;
            }

            int i = 3 * _first[r], j = 3 * _second[r], g = 3 * r;
            var si = scale * m * w[_first[r]];
            target[i] += si * _gradient[g];
            target[i + 1] += si * _gradient[g + 1];
            target[i + 2] += si * _gradient[g + 2];
            if (j >= 0)
            {
                var sj = scale * m * w[_second[r]];
                target[j] -= sj * _gradient[g];
                target[j + 1] -= sj * _gradient[g + 1];
                target[j + 2] -= sj * _gradient[g + 2];
            }
        }
    }

    /// <inheritdoc />
    public void Project(in ConstraintContext context)
    {
        if (_count == 0)
        {
            return;
        }

        EnsureTopology(context.Count);
        unsafe
        {
            fixed (double* x = context.Positions, w = &MemoryMarshal.GetReference(context.InverseMasses))
            fixed (double* anchor = _anchor, length = _length)
            fixed (int* first = _first, second = _second, order = _order)
            fixed (bool* cable = _cable)
            {
                for (var c = 0; c < _count; c++)
                {
                    var r = order[c];
                    long i = 3 * first[r];
                    var b = second[r];
                    var wi = w[first[r]];
                    var wj = b >= 0 ? w[b] : 0.0;
                    var wsum = wi + wj;
                    if (wsum == 0.0)
                    {
                        continue;
                    }

                    var pb = b >= 0 ? x + (3L * b) : anchor + (3L * r);
                    double dx = x[i] - pb[0], dy = x[i + 1] - pb[1], dz = x[i + 2] - pb[2];
                    var squared = (dx * dx) + (dy * dy) + (dz * dz);
                    if (squared == 0.0)
                    {
                        continue;
                    }

                    var l = Math.Sqrt(squared);
                    var violation = l - length[r];
                    if (cable[r] && violation <= 0.0)
                    {
                        continue;
                    }

                    // Compliance 0: dlambda = -C / (w_i + w_j), along u = d / l.
                    var scale = -violation / (wsum * l);
                    double cx = scale * dx, cy = scale * dy, cz = scale * dz;
                    x[i] += wi * cx;
                    x[i + 1] += wi * cy;
                    x[i + 2] += wi * cz;
                    if (b >= 0)
                    {
                        pb[0] -= wj * cx;
                        pb[1] -= wj * cy;
                        pb[2] -= wj * cz;
                    }
                }
            }
        }
    }

    /// <inheritdoc />
    /// <remarks>Nothing: the velocities taken from the change of positions already carry the rods and cables.</remarks>
    public void SolveVelocities(in ConstraintContext context)
    {
    }

    private int Add(int first, int second, Vector3d anchor, double length, bool cable)
    {
        Guard.ParticleIndex(first, _world.Count, nameof(first));
        if (second != Anchored)
        {
            Guard.ParticleIndex(second, _world.Count, nameof(second));
            Guard.DistinctParticles(first, second, nameof(second));
        }

        Guard.Finite(anchor, nameof(anchor));
        Guard.PositiveWithFiniteInverse(length, nameof(length), "m"); // the solve divides by it
        if (!DoubleChecks.IsFinite(length * length))
        {
            // The constraint forces use C = (|d|^2 - L^2) / 2: L^2 = infinity made every evaluation NaN.
            throw new ArgumentOutOfRangeException(
                nameof(length),
                length,
                $"length must be at most about 1.34e154 m, so that its square is finite (the constraint C = (|d|^2 - L^2) / 2 "
                + $"squares it, as a capsule's segment is); got {Guard.Format(length)}.");
        }

        _world.ThrowIfStepping();
        if (_count == _first.Length)
        {
            var capacity = Math.Max(4, 2 * _count);
            Array.Resize(ref _first, capacity);
            Array.Resize(ref _second, capacity);
            Array.Resize(ref _anchor, 3 * capacity);
            Array.Resize(ref _length, capacity);
            Array.Resize(ref _cable, capacity);
        }

        var r = _count++;
        _first[r] = first;
        _second[r] = second;
        _anchor[3 * r] = anchor.X;
        _anchor[(3 * r) + 1] = anchor.Y;
        _anchor[(3 * r) + 2] = anchor.Z;
        _length[r] = length;
        _cable[r] = cable;
        _cableCount += cable ? 1 : 0;
        _topologyStale = true;
        return r;
    }

    private int CheckedSecond(int second)
    {
        Guard.ParticleIndex(second, _world.Count, nameof(second));
        return second;
    }

    private void CheckLink(int link)
    {
        if ((uint)link >= (uint)_count)
        {
            throw new ArgumentOutOfRangeException(
                nameof(link), link, $"link must name an existing rod or cable, 0 to {_count - 1}; got {link}.");
        }
    }

    /// <summary>|d| for link r in <paramref name="x"/>, with d = x_i - x_j (or x_i - anchor).</summary>
    private double Distance(Span<double> x, int r, out double dx, out double dy, out double dz)
    {
        var i = 3 * _first[r];
        var j = 3 * _second[r];
        if (j >= 0)
        {
            dx = x[i] - x[j];
            dy = x[i + 1] - x[j + 1];
            dz = x[i + 2] - x[j + 2];
        }
        else
        {
            dx = x[i] - _anchor[3 * r];
            dy = x[i + 1] - _anchor[(3 * r) + 1];
            dz = x[i + 2] - _anchor[(3 * r) + 2];
        }

        return Math.Sqrt((dx * dx) + (dy * dy) + (dz * dz));
    }

    /// <summary>Adds s I to the 3 x 3 block of <paramref name="particle"/> (9 values per particle, row-major).</summary>
    private static void AddIsotropic(Span<double> blocks, int particle, double s)
    {
        var o = 9 * particle;
        blocks[o] += s;
        blocks[o + 4] += s;
        blocks[o + 8] += s;
    }

    private void CheckLinearized()
    {
        if (_linearizedLinks != _count || _topologyStale)
        {
            throw new InvalidOperationException(_linearizedLinks < 0
                ? "The rods' Jacobian products and blocks need a Linearize first."
                : "Rods or cables were added since the last Linearize: linearise again.");
        }
    }

    private void SetGradient(int r, double gx, double gy, double gz)
    {
        _gradient[3 * r] = gx;
        _gradient[(3 * r) + 1] = gy;
        _gradient[(3 * r) + 2] = gz;
    }

    /// <summary>Solves for the active links, then drops the cables whose multiplier would push (positive) and solves again.</summary>
    private void SolveWithPullingCables(Span<double> w)
    {
        for (var attempt = 0; attempt <= _cableCount; attempt++)
        {
            Solve(w);
            var dropped = false;
            for (var r = 0; r < _count; r++)
            {
                if (_cable[r] && _active[r] && _lambda[r] > 0.0)
                {
                    _active[r] = false;
                    dropped = true;
                }
            }

            if (!dropped)
            {
                return;
            }
        }
    }

    /// <summary>
    /// Solves (J W J^T) lambda = rhs over the active links (the others get lambda = 0), with J's rows the gradients:
    /// +g_r at the first end, -g_r at the second.
    /// </summary>
    private void Solve(Span<double> w)
    {
        if (_bandwidth <= MaxDirectBandwidth)
        {
            SolveBanded(w);
        }
        else
        {
            SolveConjugateGradients(w);
        }
    }

    private void SolveBanded(Span<double> w)
    {
        var b = _bandwidth;
        var stride = b + 1;
        var band = _band.AsSpan(0, _count * stride);
        band.Clear();
        for (var r = 0; r < _count; r++)
        {
            _lambda[r] = _active[r] ? _rhs[r] : 0.0;
            band[(r * stride) + b] = _active[r] ? DiagonalEntry(w, r) : 1.0;
            if (_active[r] && band[(r * stride) + b] == 0.0)
            {
                // Both ends immovable or no direction: nothing this link can do.
                _active[r] = false;
                band[(r * stride) + b] = 1.0;
                _lambda[r] = 0.0;
            }
        }

        // Off-diagonal entries: two active links meeting at a free particle p couple by w_p (s_r g_r) . (s_s g_s).
        for (var p = 0; p < _particles; p++)
        {
            var wp = w[p];
            if (wp == 0.0)
            {
                continue;
            }

            for (var a = _linksStart[p]; a < _linksStart[p + 1]; a++)
            {
                var r = _links[a];
                if (!_active[r])
                {
                    continue;
                }

                for (var c = a + 1; c < _linksStart[p + 1]; c++)
                {
                    var s = _links[c];
                    if (!_active[s] || s == r)
                    {
                        continue;
                    }

                    int hi = Math.Max(r, s), lo = Math.Min(r, s);
                    band[(hi * stride) + b - (hi - lo)] += wp * Sign(r, p) * Sign(s, p) * GradientDot(r, s);
                }
            }
        }

        BandedCholesky.Factor(band, _count, b);
        BandedCholesky.Solve(band, _count, b, _lambda.AsSpan(0, _count));
    }

    private void SolveConjugateGradients(Span<double> w)
    {
        var n = _count;
        var rhsNorm = 0.0;
        for (var r = 0; r < n; r++)
        {
            var d = _active[r] ? DiagonalEntry(w, r) : 0.0;
            if (!(d > 0.0))
            {
                _active[r] = false;
                d = 1.0;
            }

            _diagonal[r] = d;
            _lambda[r] = 0.0;
            var rr = _active[r] ? _rhs[r] : 0.0;
            _residual[r] = rr;
            rhsNorm += rr * rr;
        }

        rhsNorm = Math.Sqrt(rhsNorm);
        if (rhsNorm == 0.0)
        {
            return;
        }

        var rz = 0.0;
        for (var r = 0; r < n; r++)
        {
            _preconditioned[r] = _residual[r] / _diagonal[r];
            _direction[r] = _preconditioned[r];
            rz += _residual[r] * _preconditioned[r];
        }

        var target = SolveTolerance * rhsNorm;
        var maxIterations = (2 * n) + 50;
        for (var iteration = 0; iteration < maxIterations; iteration++)
        {
            var pq = MultiplyActive(w, _direction, _product);
            if (!(pq > 0.0))
            {
                break;
            }

            var alpha = rz / pq;
            var residualNorm = 0.0;
            for (var r = 0; r < n; r++)
            {
                _lambda[r] += alpha * _direction[r];
                _residual[r] -= alpha * _product[r];
                residualNorm += _residual[r] * _residual[r];
            }

            if (Math.Sqrt(residualNorm) <= target)
            {
                break;
            }

            var rzNext = 0.0;
            for (var r = 0; r < n; r++)
            {
                _preconditioned[r] = _residual[r] / _diagonal[r];
                rzNext += _residual[r] * _preconditioned[r];
            }

            var beta = rzNext / rz;
            rz = rzNext;
            for (var r = 0; r < n; r++)
            {
                _direction[r] = _preconditioned[r] + (beta * _direction[r]);
            }
        }
    }

    /// <summary>y = (J W J^T) y_in over the active links (0 elsewhere); returns y_in . y.</summary>
    private double MultiplyActive(Span<double> w, double[] input, double[] output)
    {
        var sums = _perParticle.AsSpan(0, 3 * _particles);
        sums.Clear();
        for (var r = 0; r < _count; r++)
        {
            if (!_active[r])
            {
                continue;
            }

            int i = 3 * _first[r], j = 3 * _second[r], g = 3 * r;
            var y = input[r];
            sums[i] += y * _gradient[g];
            sums[i + 1] += y * _gradient[g + 1];
            sums[i + 2] += y * _gradient[g + 2];
            if (j >= 0)
            {
                sums[j] -= y * _gradient[g];
                sums[j + 1] -= y * _gradient[g + 1];
                sums[j + 2] -= y * _gradient[g + 2];
            }
        }

        var dot = 0.0;
        for (var r = 0; r < _count; r++)
        {
            if (!_active[r])
            {
                output[r] = 0.0;
                continue;
            }

            int i = 3 * _first[r], j = 3 * _second[r], g = 3 * r;
            var wi = w[_first[r]];
            var value = wi * ((_gradient[g] * sums[i]) + (_gradient[g + 1] * sums[i + 1]) + (_gradient[g + 2] * sums[i + 2]));
            if (j >= 0)
            {
                var wj = w[_second[r]];
                value -= wj * ((_gradient[g] * sums[j]) + (_gradient[g + 1] * sums[j + 1]) + (_gradient[g + 2] * sums[j + 2]));
            }

            output[r] = value;
            dot += input[r] * value;
        }

        return dot;
    }

    /// <summary>Adds W J^T lambda into <paramref name="target"/> (positions or velocities, 3 values per particle).</summary>
    private void ApplyCorrection(Span<double> w, Span<double> target)
    {
        for (var r = 0; r < _count; r++)
        {
            var lambda = _lambda[r];
            if (!_active[r] || lambda == 0.0)
            {
                continue;
            }

            int i = 3 * _first[r], j = 3 * _second[r], g = 3 * r;
            var si = lambda * w[_first[r]];
            target[i] += si * _gradient[g];
            target[i + 1] += si * _gradient[g + 1];
            target[i + 2] += si * _gradient[g + 2];
            if (j >= 0)
            {
                var sj = lambda * w[_second[r]];
                target[j] -= sj * _gradient[g];
                target[j + 1] -= sj * _gradient[g + 1];
                target[j + 2] -= sj * _gradient[g + 2];
            }
        }
    }

    private double DiagonalEntry(Span<double> w, int r)
    {
        var squared = GradientDot(r, r);
        var sum = w[_first[r]];
        if (_second[r] >= 0)
        {
            sum += w[_second[r]];
        }

        return sum * squared;
    }

    private double GradientDot(int r, int s) =>
        (_gradient[3 * r] * _gradient[3 * s]) + (_gradient[(3 * r) + 1] * _gradient[(3 * s) + 1])
        + (_gradient[(3 * r) + 2] * _gradient[(3 * s) + 2]);

    private double Sign(int r, int particle) => _first[r] == particle ? 1.0 : -1.0;

    /// <summary>Rebuilds the links by particle, the colour order and the band of J W J^T when links or particles changed.</summary>
    private void EnsureTopology(int particles)
    {
        if (!_topologyStale && particles == _particles)
        {
            return;
        }

        if (particles < _world.Count)
        {
            throw new ArgumentException(
                $"RodNetwork needs the {_world.Count} particles of its world; the buffers hold {particles}.");
        }

        var n = _count;
        var start = new int[particles + 1];
        for (var r = 0; r < n; r++)
        {
            start[_first[r] + 1]++;
            if (_second[r] >= 0)
            {
                start[_second[r] + 1]++;
            }
        }

        for (var p = 0; p < particles; p++)
        {
            start[p + 1] += start[p];
        }

        var fill = new int[particles];
        var links = new int[start[particles]];
        var bandwidth = 0;
        for (var r = 0; r < n; r++)
        {
            links[start[_first[r]] + fill[_first[r]]++] = r;
            if (_second[r] >= 0)
            {
                links[start[_second[r]] + fill[_second[r]]++] = r;
            }
        }

        for (var p = 0; p < particles; p++)
        {
            if (start[p + 1] > start[p])
            {
                // Links are listed in increasing index at each particle: the band is last minus first.
                bandwidth = Math.Max(bandwidth, links[start[p + 1] - 1] - links[start[p]]);
            }
        }

        _linksStart = start;
        _links = links;
        _bandwidth = bandwidth;
        _order = new int[n];
        _colourStarts = ConstraintColouring.Colour(_first, _second, n, particles, _order);
        _gradient = new double[3 * n];
        _rhs = new double[n];
        _lambda = new double[n];

        // The tensions of the links there were stay what the last evaluation found (a rebuild because particles were
        // added, or links, changes none of them); new links read 0 until evaluated.
        var tension = new double[n];
        _tension.AsSpan(0, Math.Min(_tension.Length, n)).CopyTo(tension);
        _tension = tension;
        _active = new bool[n];
        _kick = new double[n];
        _kickStep = new double[n];
        _geometric = new double[n];
        _linearizedLinks = -1;
        if (bandwidth <= MaxDirectBandwidth)
        {
            _band = new double[n * (bandwidth + 1)];
        }
        else
        {
            _residual = new double[n];
            _direction = new double[n];
            _product = new double[n];
            _preconditioned = new double[n];
            _diagonal = new double[n];
            _perParticle = new double[3 * particles];
        }

        _particles = particles;
        _topologyStale = false;
    }
}
