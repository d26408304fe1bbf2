using System;
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
public sealed partial class RodNetwork : IStatefulConstraintSet, IConstraintForces, IForceJacobian
{
    /// <summary>The largest half-bandwidth of J W J^T solved by the direct band factorisation; wider ones use conjugate gradients.</summary>
    public const int MaxDirectBandwidth = 16;

    // A cable is taut when its length is at least L (1 - TautTolerance) and it shortens more slowly than
    // TautTolerance L per second.
    private const double TautTolerance = 1e-9;

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
}
