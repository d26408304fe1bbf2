using System;
using System.Runtime.InteropServices;
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
/// </remarks>
public sealed class SpringNetwork : IForceGenerator, IPotentialEnergy, IBoundForce, IJacobianCouplings, IForceLinearization, ISpringElements, IAppendOnlyCouplings
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

    ParticleWorld? IBoundForce.System => _system;

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
        _pairs.CheckIndex(spring, nameof(spring));
        Guard.NonNegativeFinite(stiffness, nameof(stiffness));
        _pairs.Parameters[PairStride * spring] = stiffness;
        _parameterVersion++;
    }

    /// <summary>Changes the axial damping of a particle-particle spring (a finite number &gt;= 0, in N s/m).</summary>
    public void SetDamping(int spring, double damping)
    {
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

    /// <inheritdoc />
    public unsafe void Linearize(
        in ParticleState state, double positionScale, double velocityScale, Span<double> positionJacobianTimesVelocity)
    {
        CheckSizes(state.Positions.Length, state.Velocities.Length, positionJacobianTimesVelocity.Length);
        EnsureLinearStorage();
        _runner = state.Runner is { MaxParallelism: > 1 } runner && _pairs.Count >= ParallelThreshold ? runner : null;
        fixed (double* x = &MemoryMarshal.GetReference(state.Positions), v = &MemoryMarshal.GetReference(state.Velocities))
        fixed (double* into = positionJacobianTimesVelocity, p = _pairs.Parameters, lin = _linear)
        fixed (int* first = _pairs.First, second = _pairs.Second)
        {
            if (_runner is not null)
            {
                _parallel ??= new ParallelSpringForces();
                _jacobian ??= new ParallelSpringJacobian();
                _parallel.Incidence.Update(_pairs, _system.Count);
                _jacobian.Linearize(x, v, p, first, second, _pairs.Count, positionScale, velocityScale, lin, into, _parallel.Incidence, _runner);
            }
            else
            {
                var count = _pairs.Count;
                var y = stackalloc double[3];
                for (var s = 0; s < count; s++)
                {
                    long a = 3 * first[s], b = 3 * second[s];
                    SpringLinearization.Pair(x, v, a, b, p + (PairStride * s), positionScale, velocityScale, lin + (LinearStride * s), y);
                    into[a] += y[0];
                    into[a + 1] += y[1];
                    into[a + 2] += y[2];
                    into[b] -= y[0];
                    into[b + 1] -= y[1];
                    into[b + 2] -= y[2];
                }
            }
        }

        LinearizeAnchored(state.Positions, state.Velocities, positionScale, velocityScale, positionJacobianTimesVelocity);
        _linearized.Record(_pairs.Count, _anchored.Count);
    }

    /// <summary>Sizes the linearisation's storage for the springs there are (5 values each).</summary>
    private void EnsureLinearStorage()
    {
        if (_linear.Length < LinearStride * _pairs.Count)
        {
            _linear = new double[LinearStride * _pairs.First.Length];
        }

        if (_anchoredLinear.Length < LinearStride * _anchored.Count)
        {
            _anchoredLinear = new double[LinearStride * _anchored.First.Length];
        }
    }

    /// <summary>Linearises the anchored springs and adds their (df/dx) v.</summary>
    private void LinearizeAnchored(
        ReadOnlySpan<double> positions, ReadOnlySpan<double> velocities, double positionScale, double velocityScale,
        Span<double> positionJacobianTimesVelocity)
    {
        var xr = positions.ForReading();
        var vr = velocities.ForReading();
        var r = _anchored.Parameters;
        for (var s = 0; s < _anchored.Count; s++)
        {
            int a = 3 * _anchored.First[s], q = AnchoredStride * s;
            var (k, iso) = LinearizeOne(
                xr[a] - r[q], xr[a + 1] - r[q + 1], xr[a + 2] - r[q + 2], r[q + 3], r[q + 4], r[q + 5],
                positionScale, velocityScale, _anchoredLinear.AsSpan(LinearStride * s, LinearStride));
            AddPositionTerm(_anchoredLinear.AsSpan(LinearStride * s, LinearStride), k, iso,
                vr[a], vr[a + 1], vr[a + 2], positionJacobianTimesVelocity, a, -1);
        }
    }

    /// <inheritdoc />
    /// <remarks>
    /// One pass over the springs where <see cref="AddForces"/>, <see cref="Linearize"/> and
    /// <see cref="AddDiagonalBlocks"/> make three: each spring's length and direction are computed once and serve its
    /// force, its linearisation and its blocks, with the same operations as those methods (the same bits).
    /// </remarks>
    public unsafe void AddForcesAndLinearize(
        in ParticleState state,
        double positionScale,
        double velocityScale,
        Span<double> forces,
        Span<double> positionJacobianTimesVelocity,
        Span<double> diagonalBlocks)
    {
        CheckSizes(state.Positions.Length, state.Velocities.Length, Math.Min(forces.Length, positionJacobianTimesVelocity.Length));
        if (diagonalBlocks.Length < 9 * _system.Count)
        {
            throw new ArgumentException(
                $"diagonalBlocks must hold 9 values per particle, {9 * _system.Count}; it holds {diagonalBlocks.Length}.", nameof(diagonalBlocks));
        }

        EnsureLinearStorage();
        _runner = state.Runner is { MaxParallelism: > 1 } runner && _pairs.Count >= ParallelThreshold ? runner : null;

        // Every pointer stays inside its array, as in AddForces and Linearize: the ends are below the particle count
        // (checked when added), the buffers hold 3 (the blocks 9) values per particle (checked above), the linear
        // storage 5 values per spring (sized above).
        fixed (double* x = &MemoryMarshal.GetReference(state.Positions), v = &MemoryMarshal.GetReference(state.Velocities))
        fixed (double* f = forces, into = positionJacobianTimesVelocity, d = diagonalBlocks, p = _pairs.Parameters, lin = _linear)
        fixed (int* first = _pairs.First, second = _pairs.Second)
        {
            if (_runner is not null)
            {
                _parallel ??= new ParallelSpringForces();
                _jacobian ??= new ParallelSpringJacobian();
                _parallel.Incidence.Update(_pairs, _system.Count);
                _jacobian.LinearizeWithForces(
                    x, v, p, first, second, _pairs.Count, positionScale, velocityScale, lin, f, into, d, _parallel.Incidence, _runner);
            }
            else
            {
                // The arithmetic of SpringLinearization.PairWithForce, written out with locals only (through the
                // helper's output pointers its values went to memory and back): the same operations, in blocks whose
                // lengths come first (SpringLengths).
                var y = stackalloc double[6]; // (for a spring of zero length only)
                var roots = stackalloc double[2 * SpringLengths.Block];
                ForcesAndLinearization(x, v, p, lin, f, into, first, second, _pairs.Count, positionScale, velocityScale, roots, y);
                GatherDiagonalBlocks(d, lin); // from the linearisation just written
            }
        }

        // The anchored springs, each of the three in its own loop (they are few): the same calls as the separate methods.
        AddAnchoredForces(state.Positions, state.Velocities, forces);
        LinearizeAnchored(state.Positions, state.Velocities, positionScale, velocityScale, positionJacobianTimesVelocity);
        _linearized.Record(_pairs.Count, _anchored.Count);
        AddAnchoredBlocks(diagonalBlocks);
    }

    /// <summary>
    /// The one-thread loop of <see cref="AddForcesAndLinearize"/> over the <paramref name="count"/> springs: forces into
    /// <paramref name="f"/>, K v into <paramref name="into"/>, the linearisation into <paramref name="lin"/>. A method of
    /// its own, with the scratch (<paramref name="roots"/>: 2 <see cref="SpringLengths.Block"/> values, <paramref name="y"/>: 6)
    /// from the caller's stack: the runtime compiles a method that allocates on the stack once, without the profile that
    /// its later compilation of this one uses, and the loop's locals fit in registers here.
    /// </summary>
    private static unsafe void ForcesAndLinearization(
        double* x, double* v, double* p, double* lin, double* f, double* into, int* first, int* second, int count,
        double positionScale, double velocityScale, double* roots, double* y)
    {
        for (var begin = 0; begin < count; begin += SpringLengths.Block)
        {
            var end = Math.Min(count, begin + SpringLengths.Block);
            SpringLengths.Compute(x, first, second, begin, end, roots);
            for (var s = begin; s < end; s++)
            {
                long a = 3 * first[s], b = 3 * second[s];
                var q = lin + (LinearStride * s);
                var c = p + (PairStride * s);
                double k = c[0], restLength = c[1], damping = c[2];
                double dx = x[a] - x[b], dy = x[a + 1] - x[b + 1], dz = x[a + 2] - x[b + 2];
                double dvx = v[a] - v[b], dvy = v[a + 1] - v[b + 1], dvz = v[a + 2] - v[b + 2];
                var length = roots[s - begin];
                double yx, yy, yz, fx, fy, fz;
                if (length == 0.0)
                {
                    SpringLinearization.PairWithForce(x, v, a, b, c, positionScale, velocityScale, roots + (s - begin), q, y, y + 3);
                    (yx, yy, yz, fx, fy, fz) = (y[0], y[1], y[2], y[3], y[4], y[5]);
                }
                else
                {
                    var inverse = roots[SpringLengths.Block + (s - begin)];
                    var transverse = Math.Max(0.0, 1.0 - (restLength * inverse));
                    double ux = dx * inverse, uy = dy * inverse, uz = dz * inverse;
                    var iso = k * transverse;
                    var axial = k * (1.0 - transverse);
                    var t = -((positionScale * k * (1.0 - transverse)) + (velocityScale * damping));
                    var sIso = -positionScale * k * transverse;
                    q[0] = ux;
                    q[1] = uy;
                    q[2] = uz;
                    q[3] = sIso;
                    q[4] = t;
                    var closing = (ux * dvx) + (uy * dvy) + (uz * dvz);
                    var along = axial * closing;
                    yx = -((iso * dvx) + (along * ux));
                    yy = -((iso * dvy) + (along * uy));
                    yz = -((iso * dvz) + (along * uz));
                    var magnitude = (k * (length - restLength)) + (damping * closing);
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
                into[a] += yx;
                into[a + 1] += yy;
                into[a + 2] += yz;
                into[b] -= yx;
                into[b + 1] -= yy;
                into[b + 2] -= yz;
            }
        }
    }

    /// <inheritdoc />
    public unsafe void AddJacobianProduct(ReadOnlySpan<double> w, Span<double> result)
    {
        var wr = w.ForReading();
        CheckSizes(w.Length, w.Length, result.Length);
        _linearized.Check(nameof(SpringNetwork), _pairs.Count, _anchored.Count);
        if (_linear.Length < LinearStride * _pairs.Count)
        {
            // Unreachable after the check above (Linearize sized it for Count springs); kept where the pointer is taken.
            throw new InvalidOperationException("SpringNetwork's linearisation is shorter than its springs.");
        }

        // The hot loop of every conjugate-gradient iteration: pointers for the same reason as in AddForces; the
        // linearisation covers exactly the Count springs (checked above). On one thread one part, all the springs; on a
        // runner each part of the particles sums its own springs' terms, with the same bits (SpringJacobianProduct).
        fixed (double* wp = &MemoryMarshal.GetReference(w), y = result, lin = _linear)
        {
            // (One instance for each, so that a host switching between a runner and none does not rebuild the parts.)
            var product = _runner is null ? _product ??= new SpringJacobianProduct() : _parallelProduct ??= new SpringJacobianProduct();
            product.Product(
                wp, y, lin, _pairs, _pairs.Count, _topologyVersion, _system.Count, _runner is null ? 1 : ProductPartsPerThread * _runner.MaxParallelism, _runner);
        }

        var anchoredLin = _anchoredLinear;
        for (var s = 0; s < _anchored.Count; s++)
        {
            int a = 3 * _anchored.First[s], q = LinearStride * s;
            double dx = wr[a], dy = wr[a + 1], dz = wr[a + 2];
            double ux = anchoredLin[q], uy = anchoredLin[q + 1], uz = anchoredLin[q + 2], iso = anchoredLin[q + 3];
            var axial = anchoredLin[q + 4] * ((ux * dx) + (uy * dy) + (uz * dz));
            result[a] += (iso * dx) + (axial * ux);
            result[a + 1] += (iso * dy) + (axial * uy);
            result[a + 2] += (iso * dz) + (axial * uz);
        }
    }

    /// <inheritdoc />
    public unsafe void AddDiagonalBlocks(Span<double> blocks)
    {
        _linearized.Check(nameof(SpringNetwork), _pairs.Count, _anchored.Count);
        if (blocks.Length < 9 * _system.Count)
        {
            throw new ArgumentException($"blocks must hold 9 values per particle, {9 * _system.Count}; it holds {blocks.Length}.", nameof(blocks));
        }

        fixed (double* d = blocks, lin = _linear)
        {
            if (_runner is not null && _jacobian is not null && _parallel is not null)
            {
                _jacobian.DiagonalBlocks(d, lin, _parallel.Incidence, _runner);
            }
            else
            {
                GatherDiagonalBlocks(d, lin);
            }
        }

        AddAnchoredBlocks(blocks);
    }

    /// <summary>
    /// Adds the springs' diagonal blocks on one thread, gathered per particle in increasing spring order: the sums a
    /// spring-by-spring scatter into both ends gives, with 9 stores per particle instead of 9 read-modify-writes per
    /// spring end (the parallel pass gathers the same way, so every path gives the same bits).
    /// </summary>
    private unsafe void GatherDiagonalBlocks(double* blocks, double* linear)
    {
        _parallel ??= new ParallelSpringForces();
        var incidence = _parallel.Incidence;
        incidence.Update(_pairs, _system.Count);
        fixed (int* start = incidence.Start, incident = incidence.Incident)
        {
            SpringLinearization.GatherBlocks(blocks, linear, start, incident, 0, _system.Count);
        }
    }

    /// <summary>Adds the anchored springs' diagonal blocks (their only block: the anchor does not move).</summary>
    private void AddAnchoredBlocks(Span<double> blocks)
    {
        for (var s = 0; s < _anchored.Count; s++)
        {
            var q = LinearStride * s;
            JacobianBlocks.Add(
                blocks, _anchored.First[s], _anchoredLinear[q + 3], _anchoredLinear[q + 4],
                _anchoredLinear[q], _anchoredLinear[q + 1], _anchoredLinear[q + 2]);
        }
    }

    /// <inheritdoc />
    public int CouplingCount => _pairs.Count;

    /// <inheritdoc />
    public void WriteCouplings(Span<int> first, Span<int> second) => LinearPairTerms.WriteCouplings(_pairs, first, second);

    /// <inheritdoc />
    /// <remarks>Spring s adds s I + t u u^T to J_ii and J_jj, and its opposite to J_ij = J_ji.</remarks>
    public unsafe void AddCouplingBlocks(Span<double> destination, ReadOnlySpan<int> forwardBlock, ReadOnlySpan<int> backwardBlock)
    {
        LinearPairTerms.CheckTargets(_pairs.Count, destination.Length, forwardBlock, backwardBlock);
        _linearized.Check(nameof(SpringNetwork), _pairs.Count, _anchored.Count);
        fixed (double* c = destination, lin = _linear)
        fixed (int* forward = &MemoryMarshal.GetReference(forwardBlock), backward = &MemoryMarshal.GetReference(backwardBlock))
        {
            var count = _pairs.Count;
            for (var s = 0; s < count; s++)
            {
                int f = forward[s], b = backward[s];
                if ((f | b) >= 0)
                {
                    SpringLinearization.SubtractBlock(c + (9L * f), c + (9L * b), lin + (LinearStride * s));
                }
                else if (f >= 0 || b >= 0)
                {
                    var block = c + (9L * Math.Max(f, b));
                    SpringLinearization.SubtractBlock(block, block, lin + (LinearStride * s), once: true);
                }
            }
        }
    }

    /// <summary>
    /// Writes (ux, uy, uz, s, t) with a df/dx + b df/dv = s I + t u u^T for one spring of separation d; returns
    /// the position-only parts -k (transverse I + (1 - transverse) u u^T) as (k times (1 - transverse), k transverse).
    /// </summary>
    private static (double Axial, double Isotropic) LinearizeOne(
        double dx, double dy, double dz, double k, double restLength, double c, double a, double b, Span<double> into)
    {
        var lengthSquared = (dx * dx) + (dy * dy) + (dz * dz);
        if (lengthSquared == 0.0)
        {
            // No direction: a zero-rest-length spring is still -k I; a spring with a rest length exerts no force here.
            var isotropic = restLength == 0.0 ? k : 0.0;
            into[0] = into[1] = into[2] = into[4] = 0.0;
            into[3] = -a * isotropic;
            return (0.0, isotropic);
        }

        var length = Math.Sqrt(lengthSquared);
        var inverse = 1.0 / length;
        var transverse = Math.Max(0.0, 1.0 - (restLength * inverse));
        into[0] = dx * inverse;
        into[1] = dy * inverse;
        into[2] = dz * inverse;
        into[3] = -a * k * transverse;
        into[4] = -((a * k * (1.0 - transverse)) + (b * c));
        return (k * (1.0 - transverse), k * transverse);
    }

    /// <summary>Adds df/dx (v_i - v_j) = -(iso dv + axial (u . dv) u) at end a, its opposite at end b.</summary>
    private static void AddPositionTerm(
        ReadOnlySpan<double> linear, double axial, double iso, double dvx, double dvy, double dvz, Span<double> into, int a, int b)
    {
        var u = linear.ForReading();
        var along = axial * ((u[0] * dvx) + (u[1] * dvy) + (u[2] * dvz));
        double yx = -((iso * dvx) + (along * u[0]));
        double yy = -((iso * dvy) + (along * u[1]));
        double yz = -((iso * dvz) + (along * u[2]));
        into[a] += yx;
        into[a + 1] += yy;
        into[a + 2] += yz;
        if (b >= 0)
        {
            into[b] -= yx;
            into[b + 1] -= yy;
            into[b + 2] -= yz;
        }
    }
}
