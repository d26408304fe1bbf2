using System;
using System.Runtime.InteropServices;
using ParticlePhysics.Internal;
using ParticlePhysics.Numerics;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Forces;

/// <summary>
/// Hooke springs with a rest length and damping along their axis, between two particles or a particle and a fixed
/// anchor (zero velocity). With d = x_i - x_j, l = |d| and u = d / l:
/// F_i = -(k (l - L) + c (v_i - v_j) . u) u and F_j = -F_i. When l = 0 the direction is undefined and the force
/// is zero (never NaN). Potential energy: k (l - L)^2 / 2 per spring. One generator holds a whole network
/// (a cloth's thousands of springs) in flat arrays and is evaluated in one call.
/// </summary>
/// <remarks>
/// Jacobian (for implicit integration), per spring: df_i/dx_i = -k (t I + (1 - t) u u^T) with
/// t = max(0, 1 - L / l), df_i/dv_i = -c u u^T, and df_i/dx_j = -df_i/dx_i, df_i/dv_j = -df_i/dv_i.
/// The clamp of t keeps a compressed spring from making the implicit system indefinite (Baraff and Witkin 1998,
/// Choi and Ko 2002); the position derivative of the damping term, which is not symmetric and vanishes when the
/// ends move together, is left out. Each linearised spring is stored as u and two scalars, s I + t u u^T.
/// The elements, forces and energy are here; the Jacobian (linearisation, products, diagonal and coupling blocks) is
/// in SpringNetwork.Jacobian.cs.
/// </remarks>
public sealed partial class SpringNetwork : IForceGenerator, IPotentialEnergy, IBoundForce, IJacobianCouplings, IForceLinearization, ISpringElements, IAppendOnlyCouplings
{
    // Pair parameters: k, L, c. Anchored parameters: ax, ay, az, k, L, c.
    private const int PairStride = 3;
    private const int AnchoredStride = 6;
    private readonly ForceElements _pairs = new(PairStride);
    private readonly ForceElements _anchored = new(AnchoredStride);
    private readonly ParticleWorld _system;

    // Linearisation, 5 values per spring: ux, uy, uz, s, t for the block s I + t u u^T.
    private const int LinearStride = 5;
    private double[] _linear = Array.Empty<double>();
    private double[] _anchoredLinear = Array.Empty<double>();
    private LinearizationStamp _linearized;

    // Parallel evaluation: below this many springs, waking other threads costs more than it saves.
    private const int ParallelThreshold = 4096;
    private ParallelSpringForces? _parallel;
    private int _topologyVersion;
    private int _parameterVersion;
    private ParallelSpringJacobian? _jacobian;
    private SpringJacobianProduct? _product;
    private SpringJacobianProduct? _parallelProduct;

    /// <summary>For tests: the product's parts on the last runner it ran on (null before).</summary>
    internal SpringJacobianProduct? ParallelProduct => _parallelProduct;

    // The product's parts per thread of a runner: two, so that a thread that finishes early takes another part.
    private const int ProductPartsPerThread = 2;
    private IParallelRunner? _runner; // the runner of the last Linearize, for the products that use it

    /// <summary>An empty network for the particles of <paramref name="system"/>.</summary>
    public SpringNetwork(ParticleWorld system)
    {
        Guard.NotNull(system, nameof(system));
        _system = system;
    }

    /// <summary>The number of springs between two particles.</summary>
    public int Count => _pairs.Count;

    /// <summary>The number of springs between a particle and a fixed anchor.</summary>
    public int AnchoredCount => _anchored.Count;

    object? IBoundForce.World => _system;

    /// <inheritdoc />
    public int TopologyVersion => _topologyVersion;

    /// <inheritdoc />
    public int ParameterVersion => _parameterVersion;

    /// <inheritdoc />
    int ISpringElements.PairCount => _pairs.Count;

    /// <inheritdoc />
    public void CopyPairs(Span<int> first, Span<int> second, Span<double> parameters)
    {
        _pairs.First.AsSpan(0, _pairs.Count).CopyTo(first);
        _pairs.Second.AsSpan(0, _pairs.Count).CopyTo(second);
        _pairs.Parameters.AsSpan(0, PairStride * _pairs.Count).CopyTo(parameters);
    }

    /// <inheritdoc />
    public void CopyAnchored(Span<int> particle, Span<double> parameters)
    {
        _anchored.First.AsSpan(0, _anchored.Count).CopyTo(particle);
        _anchored.Parameters.AsSpan(0, AnchoredStride * _anchored.Count).CopyTo(parameters);
    }

    /// <summary>Adds a spring between two different existing particles.</summary>
    /// <param name="first">One end (i).</param>
    /// <param name="second">The other end (j).</param>
    /// <param name="stiffness">k, in N/m: a finite number &gt;= 0.</param>
    /// <param name="restLength">L, in metres: a finite number &gt;= 0.</param>
    /// <param name="damping">c, in N s/m, along the spring's axis: a finite number &gt;= 0.</param>
    /// <returns>The index of the new spring among the particle-particle springs.</returns>
    public int Add(int first, int second, double stiffness, double restLength, double damping = 0.0)
    {
        _system.ThrowIfStepping();
        Guard.ParticleIndex(first, _system.Count, nameof(first));
        Guard.ParticleIndex(second, _system.Count, nameof(second));
        Guard.DistinctParticles(first, second, nameof(second));
        CheckParameters(stiffness, restLength, damping);
        Span<double> p = stackalloc double[] { stiffness, restLength, damping };
        _topologyVersion++;
        return _pairs.Add(first, second, p);
    }

    /// <summary>Adds a spring between an existing particle and a fixed anchor point.</summary>
    /// <param name="particle">The particle (i).</param>
    /// <param name="anchor">The anchor's position (x_j), in metres; its velocity is zero.</param>
    /// <param name="stiffness">k, in N/m: a finite number &gt;= 0.</param>
    /// <param name="restLength">L, in metres: a finite number &gt;= 0.</param>
    /// <param name="damping">c, in N s/m, along the spring's axis: a finite number &gt;= 0.</param>
    /// <returns>The index of the new spring among the anchored springs.</returns>
    public int AddAnchored(int particle, Vector3d anchor, double stiffness, double restLength, double damping = 0.0)
    {
        _system.ThrowIfStepping();
        Guard.ParticleIndex(particle, _system.Count, nameof(particle));
        Guard.Finite(anchor, nameof(anchor));
        CheckParameters(stiffness, restLength, damping);
        Span<double> p = stackalloc double[] { anchor.X, anchor.Y, anchor.Z, stiffness, restLength, damping };
        _topologyVersion++;
        return _anchored.Add(particle, -1, p);
    }

    /// <summary>Changes the stiffness of a particle-particle spring (a finite number &gt;= 0, in N/m).</summary>
    public void SetStiffness(int spring, double stiffness)
    {
        _system.ThrowIfStepping();
        _pairs.CheckIndex(spring, nameof(spring));
        Guard.NonNegativeFinite(stiffness, nameof(stiffness));
        _pairs.Parameters[PairStride * spring] = stiffness;
        _parameterVersion++;
    }

    /// <summary>Changes the axial damping of a particle-particle spring (a finite number &gt;= 0, in N s/m).</summary>
    public void SetDamping(int spring, double damping)
    {
        _system.ThrowIfStepping();
        _pairs.CheckIndex(spring, nameof(spring));
        Guard.NonNegativeFinite(damping, nameof(damping));
        _pairs.Parameters[(PairStride * spring) + 2] = damping;
        _parameterVersion++;
    }

    /// <summary>The two particles joined by a particle-particle spring.</summary>
    public (int First, int Second) GetEnds(int spring)
    {
        _pairs.CheckIndex(spring, nameof(spring));
        return (_pairs.First[spring], _pairs.Second[spring]);
    }

    /// <summary>The particle and the fixed anchor point of an anchored spring (what a renderer draws).</summary>
    /// <param name="spring">The index of the spring among the anchored springs, 0 to <see cref="AnchoredCount"/> - 1.</param>
    public (int Particle, Vector3d Anchor) GetAnchoredSpring(int spring)
    {
        _anchored.CheckIndex(spring, nameof(spring));
        var p = _anchored.Parameters;
        return (_anchored.First[spring], new Vector3d(p[AnchoredStride * spring], p[(AnchoredStride * spring) + 1], p[(AnchoredStride * spring) + 2]));
    }

    /// <summary>The rest length L of a particle-particle spring, in metres.</summary>
    public double GetRestLength(int spring)
    {
        _pairs.CheckIndex(spring, nameof(spring));
        return _pairs.Parameters[(PairStride * spring) + 1];
    }

    /// <inheritdoc />
    public unsafe void AddForces(in ParticleState state, Span<double> forces)
    {
        CheckSizes(state.Positions.Length, state.Velocities.Length, forces.Length);
        if (state.Runner is { MaxParallelism: > 1 } runner && _pairs.Count >= ParallelThreshold)
        {
            _parallel ??= new ParallelSpringForces();
            _parallel.AddForces(_pairs, _system.Count, state.Positions, state.Velocities, forces, runner);
            AddAnchoredForces(state.Positions, state.Velocities, forces);
            return;
        }

        // The hot loop of every explicit step: pointers, because each spring gathers and scatters by index and the
        // bounds check of every access would otherwise cost as much as the arithmetic. Every pointer stays inside its
        // array: the indices were checked against the world's count when added (the count never falls), CheckSizes
        // checked the buffers against that count, and the element arrays hold at least Count elements.
        fixed (double* x = &MemoryMarshal.GetReference(state.Positions), v = &MemoryMarshal.GetReference(state.Velocities))
        fixed (double* f = forces, p = _pairs.Parameters)
        fixed (int* first = _pairs.First, second = _pairs.Second)
        {
            var count = _pairs.Count;
            for (var s = 0; s < count; s++)
            {
                // 64-bit offsets, so that x[a + 1] is a single base + index + displacement address.
                long a = 3 * first[s], b = 3 * second[s];
                var q = p + (PairStride * s);
                double dx = x[a] - x[b], dy = x[a + 1] - x[b + 1], dz = x[a + 2] - x[b + 2];
                var lengthSquared = (dx * dx) + (dy * dy) + (dz * dz);
                double fx = 0.0, fy = 0.0, fz = 0.0;
                if (lengthSquared != 0.0)
                {
                    // (At l = 0 the zero force is still added, as the parallel pass does, so both give the same bits.)
                    var length = Math.Sqrt(lengthSquared);
                    var inverse = 1.0 / length;
                    double ux = dx * inverse, uy = dy * inverse, uz = dz * inverse;
                    var closing = ((v[a] - v[b]) * ux) + ((v[a + 1] - v[b + 1]) * uy) + ((v[a + 2] - v[b + 2]) * uz);
                    var magnitude = (q[0] * (length - q[1])) + (q[2] * closing);
                    fx = magnitude * ux;
                    fy = magnitude * uy;
                    fz = magnitude * uz;
                }

                f[a] -= fx;
                f[a + 1] -= fy;
                f[a + 2] -= fz;
                f[b] += fx;
                f[b + 1] += fy;
                f[b + 2] += fz;
            }
        }

        AddAnchoredForces(state.Positions, state.Velocities, forces);
    }

    private void AddAnchoredForces(ReadOnlySpan<double> x0, ReadOnlySpan<double> v0, Span<double> forces)
    {
        var x = x0.ForReading();
        var v = v0.ForReading();
        var particle = _anchored.First;
        var r = _anchored.Parameters;
        for (var s = 0; s < _anchored.Count; s++)
        {
            int a = 3 * particle[s], q = AnchoredStride * s;
            double dx = x[a] - r[q], dy = x[a + 1] - r[q + 1], dz = x[a + 2] - r[q + 2];
            var lengthSquared = (dx * dx) + (dy * dy) + (dz * dz);
            if (lengthSquared == 0.0)
            {
                continue;
            }

            var length = Math.Sqrt(lengthSquared);
            var inverse = 1.0 / length;
            double ux = dx * inverse, uy = dy * inverse, uz = dz * inverse;
            var closing = (v[a] * ux) + (v[a + 1] * uy) + (v[a + 2] * uz);
            var magnitude = (r[q + 3] * (length - r[q + 4])) + (r[q + 5] * closing);
            forces[a] -= magnitude * ux;
            forces[a + 1] -= magnitude * uy;
            forces[a + 2] -= magnitude * uz;
        }
    }

    /// <inheritdoc />
    public double PotentialEnergy(in ParticleState state)
    {
        var x = state.Positions.ForReading();
        var sum = 0.0;
        for (var s = 0; s < _pairs.Count; s++)
        {
            int a = 3 * _pairs.First[s], b = 3 * _pairs.Second[s], q = PairStride * s;
            double dx = x[a] - x[b], dy = x[a + 1] - x[b + 1], dz = x[a + 2] - x[b + 2];
            var stretch = Math.Sqrt((dx * dx) + (dy * dy) + (dz * dz)) - _pairs.Parameters[q + 1];
            sum += 0.5 * _pairs.Parameters[q] * stretch * stretch;
        }

        var r = _anchored.Parameters;
        for (var s = 0; s < _anchored.Count; s++)
        {
            int a = 3 * _anchored.First[s], q = AnchoredStride * s;
            double dx = x[a] - r[q], dy = x[a + 1] - r[q + 1], dz = x[a + 2] - r[q + 2];
            var stretch = Math.Sqrt((dx * dx) + (dy * dy) + (dz * dz)) - r[q + 4];
            sum += 0.5 * r[q + 3] * stretch * stretch;
        }

        return sum;
    }

    /// <summary>
    /// The pointer loops trust that every index stored is below the particle count, which Add checked against the
    /// system; this checks, once per call, that the buffers are the system's size.
    /// </summary>
    private void CheckSizes(int positions, int velocities, int result)
    {
        var needed = 3 * _system.Count;
        if (positions < needed || velocities < needed || result < needed)
        {
            throw new ArgumentException(
                $"SpringNetwork needs buffers of {needed} values (3 per particle of its system); got {positions}, {velocities} and {result}.");
        }
    }

    private static void CheckParameters(double stiffness, double restLength, double damping)
    {
        Guard.NonNegativeFinite(stiffness, nameof(stiffness));
        Guard.NonNegativeFinite(restLength, nameof(restLength));
        Guard.NonNegativeFinite(damping, nameof(damping));
    }
}
