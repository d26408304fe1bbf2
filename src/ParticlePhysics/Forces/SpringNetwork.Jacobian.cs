using System;
using System.Runtime.InteropServices;
using ParticlePhysics.Numerics;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Forces;

/// <summary>
/// The spring network's Jacobian for implicit integration (derivation in SpringNetwork.cs): its linearisation at a
/// state, alone or fused with the forces, the products J w, the diagonal blocks and the coupling blocks.
/// </summary>
public sealed partial class SpringNetwork
{
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
