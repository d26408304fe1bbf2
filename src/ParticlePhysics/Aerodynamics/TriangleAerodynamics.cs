using System;
using System.Runtime.InteropServices;
using ParticlePhysics.Forces;
using ParticlePhysics.Internal;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Aerodynamics;

/// <summary>
/// The air's force on the triangles of a cloth, each a flat plate: pressure drag along its normal and lift across the
/// flow, as the scene contract fixes them. Per triangle of area A and unit normal n, with v_rel = u - (v0 + v1 + v2) / 3
/// (u the air's velocity at the centroid), s = |v_rel| and v_n = v_rel . n:
/// F_d = 1/2 rho C_d A |v_n| v_n n, F_l = 1/2 rho C_l A v_n s w / |w| with w = n - (v_n / s^2) v_rel (0 when s = 0 or
/// w = 0), and a third of F_d + F_l on each corner. Both are even in n, so a triangle's winding does not matter.
/// </summary>
/// <remarks>
/// <para>
/// Lift, computed without s: write v_rel = v_n n + r_t (r_t in the plate's plane, t = |r_t|, so s^2 = v_n^2 + t^2).
/// Then w = (t^2 n - v_n r_t) / s^2, |w| = t / s and s w / |w| = t n - (v_n / t) r_t, so
/// F_l = 1/2 rho C_l A v_n (t n - (v_n / t) r_t): one square root and one division, and w = 0 exactly when r_t = 0
/// (taken as 0 within 1e-12 rad of the normal, where its direction is rounding's). With N = (x1 - x0) x (x2 - x0)
/// and d = v_rel . N = v_n |N|, the drag's A |v_n| v_n n = |d| d N / (2 |N|^2) needs no square root; with
/// T = |N|^2 r_t = |N|^2 v_rel - d N and Q = |N| |T| the lift's A v_n (t n - (v_n / t) r_t) =
/// d (|T|^2 N - d |N|^2 T) / (2 Q |N|^2) needs one, and one division serves both (1 / |N|^2 = Q / (Q |N|^2)). The
/// products reach |N|^6 |v_rel|^2: within range for edges from 1e-25 m to 1e25 m.
/// At angle of attack alpha (v_n = s sin alpha, t = s cos alpha) its size is 1/2 rho C_l A s^2 sin alpha, and the
/// drag's 1/2 rho C_d A s^2 sin^2 alpha.
/// </para>
/// <para>
/// Jacobian (implicit Euler). dv_rel/dv_k = -I/3 for each corner k and each corner gets a third, so
/// df_j/dv_k = -(1/9) dF/dv_rel. The drag's dF_d/dv_rel = rho C_d A |v_n| n n^T is symmetric positive semi-definite:
/// J_jk = -(b/9) rho C_d A |v_n| n n^T for all nine corner pairs, the damping that keeps a light cloth in a strong wind
/// stable, taken whole. The lift's velocity derivative is neither symmetric nor definite (across the flow it is
/// -1/2 rho C_l A v_n^2 / t, anti-damping, unbounded as t -&gt; 0), and the position derivatives (n and A turning with
/// the shape) are not symmetric either; they enter the step at its start, as an explicit force does, as the springs
/// leave out their non-symmetric parts. The couplings are the triangles' edges.
/// </para>
/// </remarks>
public sealed class TriangleAerodynamics : IForceGenerator, IBoundForce, IJacobianCouplings, IAppendOnlyCouplings
{
    private const int LinearStride = 4; // n (3), K = b rho C_d A |v_n| / 9
    private const double Third = 1.0 / 3.0;

    // n is a unit vector only to rounding, so a flow along it leaves an r_t of a few units in the last place of s,
    // whose direction is noise: below 1e-12 |v_n| (1e-12 rad off the normal) r_t is taken as 0, the contract's w = 0.
    private const double FlowAlongNormal = 1e-12;

    private readonly ParticleWorld _system;
    private Air _air;
    private int[] _corners = Array.Empty<int>();
    private double[] _linear = Array.Empty<double>();
    private int _count;
    private LinearizationStamp _linearized;

    /// <summary>No triangles yet, in <paramref name="air"/>, for the particles of <paramref name="system"/>.</summary>
    public TriangleAerodynamics(ParticleWorld system, Air air)
    {
        Guard.NotNull(system, nameof(system));
        Guard.NotNull(air, nameof(air));
        _system = system;
        _air = air;
    }

    /// <summary>The air the triangles move in; can be replaced between steps.</summary>
    public Air Air
    {
        get => _air;
        set
        {
            _system.ThrowIfStepping();
            Guard.NotNull(value, nameof(Air));
            _air = value;
        }
    }

    /// <summary>The number of triangles.</summary>
    public int Count => _count;

    object? IBoundForce.World => _system;

    /// <summary>Adds a triangle of three distinct existing particles; returns its index.</summary>
    public int Add(int first, int second, int third)
    {
        _system.ThrowIfStepping();
        Guard.ParticleIndex(first, _system.Count, nameof(first));
        Guard.ParticleIndex(second, _system.Count, nameof(second));
        Guard.ParticleIndex(third, _system.Count, nameof(third));
        Guard.DistinctParticles(first, second, nameof(second));
        Guard.DistinctParticles(first, third, nameof(third));
        Guard.DistinctParticles(second, third, nameof(third));
        if (3 * _count == _corners.Length)
        {
            Array.Resize(ref _corners, 3 * Math.Max(8, 2 * _count));
        }

        _corners[3 * _count] = first;
        _corners[(3 * _count) + 1] = second;
        _corners[(3 * _count) + 2] = third;
        return _count++;
    }

    /// <summary>The three corners of a triangle.</summary>
    public (int First, int Second, int Third) GetCorners(int triangle)
    {
        if ((uint)triangle >= (uint)_count)
        {
            throw new ArgumentOutOfRangeException(nameof(triangle), triangle, $"triangle must name an existing triangle, 0 to {_count - 1}; got {triangle}.");
        }

        return (_corners[3 * triangle], _corners[(3 * triangle) + 1], _corners[(3 * triangle) + 2]);
    }

    /// <inheritdoc />
    public void AddForces(in ParticleState state, Span<double> forces)
    {
        CheckSizes(state.Positions.Length, state.Velocities.Length, forces.Length);
        var air = _air;
        var drag = 0.5 * air.Density * air.DragCoefficient * Third;     // a third to each corner, folded in
        var lift = 0.5 * air.Density * air.LiftCoefficient * Third;
        var gust = air.Gust;
        double ux = air.Velocity.X, uy = air.Velocity.Y, uz = air.Velocity.Z;
        var time = state.Time;
        unsafe
        {
            // CheckSizes: the buffers hold every particle, and every corner is one (checked in Add).
            fixed (double* xp = &MemoryMarshal.GetReference(state.Positions), vp = &MemoryMarshal.GetReference(state.Velocities), fp = forces)
            fixed (int* corners = _corners)
            {
                for (var t = 0; t < _count; t++)
                {
                    int i0 = 3 * corners[3 * t], i1 = 3 * corners[(3 * t) + 1], i2 = 3 * corners[(3 * t) + 2];
                    double ax = xp[i1] - xp[i0], ay = xp[i1 + 1] - xp[i0 + 1], az = xp[i1 + 2] - xp[i0 + 2];
                    double bx = xp[i2] - xp[i0], by = xp[i2 + 1] - xp[i0 + 1], bz = xp[i2 + 2] - xp[i0 + 2];
                    double cx = (ay * bz) - (az * by), cy = (az * bx) - (ax * bz), cz = (ax * by) - (ay * bx);
                    var squared = (cx * cx) + (cy * cy) + (cz * cz); // |N|^2 = 4 A^2
                    if (!(squared > 0.0))
                    {
                        continue; // a collapsed triangle has no area for the air to push
                    }

                    if (gust is not null)
                    {
                        var centroid = new Vector3d(
                            (xp[i0] + xp[i1] + xp[i2]) * Third, (xp[i0 + 1] + xp[i1 + 1] + xp[i2 + 1]) * Third, (xp[i0 + 2] + xp[i1 + 2] + xp[i2 + 2]) * Third);
                        var g = gust.VelocityAt(time, centroid);
                        ux = air.Velocity.X + g.X;
                        uy = air.Velocity.Y + g.Y;
                        uz = air.Velocity.Z + g.Z;
                    }

                    var rx = ux - ((vp[i0] + vp[i1] + vp[i2]) * Third);
                    var ry = uy - ((vp[i0 + 1] + vp[i1 + 1] + vp[i2 + 1]) * Third);
                    var rz = uz - ((vp[i0 + 2] + vp[i1 + 2] + vp[i2 + 2]) * Third);
                    var d = (rx * cx) + (ry * cy) + (rz * cz); // v_n |N|
                    double fx, fy, fz;
                    if (lift != 0.0 && d != 0.0)
                    {
                        // T = |N|^2 v_rel - d N = |N|^2 r_t and Q = |N| |T| (no division on the way), then one division:
                        // R = 1 / (Q |N|^2), 1 / |N|^2 = Q R, and the lift's A v_n (t n - (v_n / t) r_t) =
                        // (d / 2) R (|T|^2 N - d |N|^2 T).
                        double tx = (squared * rx) - (d * cx), ty = (squared * ry) - (d * cy), tz = (squared * rz) - (d * cz);
                        var tt = (tx * tx) + (ty * ty) + (tz * tz);
                        var q = Math.Sqrt(squared * tt);
                        if (q > FlowAlongNormal * Math.Abs(d) * squared)
                        {
                            var r = 1.0 / (q * squared);
                            var k = 0.5 * lift * d * r;
                            var alongN = (0.5 * drag * Math.Abs(d) * d * (q * r)) + (k * tt);
                            var inPlane = k * d * squared;
                            fx = (alongN * cx) - (inPlane * tx);
                            fy = (alongN * cy) - (inPlane * ty);
                            fz = (alongN * cz) - (inPlane * tz);
                        }
                        else
                        {
                            var alongN = 0.5 * drag * Math.Abs(d) * d / squared;
                            fx = alongN * cx;
                            fy = alongN * cy;
                            fz = alongN * cz;
                        }
                    }
                    else
                    {
                        // A |v_n| v_n n = (|N| / 2) |d| d N / |N|^3 = |d| d N / (2 |N|^2): no square root.
                        var alongN = 0.5 * drag * Math.Abs(d) * d / squared;
                        fx = alongN * cx;
                        fy = alongN * cy;
                        fz = alongN * cz;
                    }

                    fp[i0] += fx;
                    fp[i0 + 1] += fy;
                    fp[i0 + 2] += fz;
                    fp[i1] += fx;
                    fp[i1 + 1] += fy;
                    fp[i1 + 2] += fz;
                    fp[i2] += fx;
                    fp[i2 + 1] += fy;
                    fp[i2 + 2] += fz;
                }
            }
        }
    }

    /// <inheritdoc />
    public void Linearize(
        in ParticleState state, double positionScale, double velocityScale, Span<double> positionJacobianTimesVelocity)
    {
        CheckSizes(state.Positions.Length, state.Velocities.Length, positionJacobianTimesVelocity.Length);
        if (_linear.Length < LinearStride * _count)
        {
            _linear = new double[LinearStride * (_corners.Length / 3)];
        }

        // Per triangle n and K = (b / 9) rho C_d A |v_n| (once a step: the square roots cost little here).
        var air = _air;
        var scale = velocityScale * air.Density * air.DragCoefficient / 9.0;
        var x = state.Positions.ForReading();
        var v = state.Velocities.ForReading();
        for (var t = 0; t < _count; t++)
        {
            int i0 = _corners[3 * t], i1 = _corners[(3 * t) + 1], i2 = _corners[(3 * t) + 2];
            Vector3d x0 = Read(x, i0), x1 = Read(x, i1), x2 = Read(x, i2);
            var cross = Vector3d.Cross(x1 - x0, x2 - x0);
            var twice = cross.Length;
            var l = _linear.AsSpan(LinearStride * t, LinearStride);
            if (!(twice > 0.0))
            {
                l.Clear();
                continue;
            }

            var n = cross / twice;
            var centroid = (x0 + x1 + x2) * Third;
            var relative = air.VelocityAt(state.Time, centroid) - ((Read(v, i0) + Read(v, i1) + Read(v, i2)) * Third);
            l[0] = n.X;
            l[1] = n.Y;
            l[2] = n.Z;
            l[3] = scale * 0.5 * twice * Math.Abs(Vector3d.Dot(relative, n));
        }

        _linearized.Record(_count, 0);
    }

    // A Span, not a ReadOnlySpan: the read-only indexer does not bind on Mono (Numerics/ReadOnlySpans).
    private static Vector3d Read(Span<double> values, int particle) =>
        new(values[3 * particle], values[(3 * particle) + 1], values[(3 * particle) + 2]);

    /// <inheritdoc />
    public void AddJacobianProduct(ReadOnlySpan<double> w, Span<double> result)
    {
        _linearized.Check(nameof(TriangleAerodynamics), _count, 0);
        CheckSizes(w.Length, w.Length, result.Length);
        unsafe
        {
            // CheckSizes: w and result hold every particle, every corner is one, and the linearisation holds _count.
            fixed (double* wp = &MemoryMarshal.GetReference(w), rp = result, lp = _linear)
            fixed (int* corners = _corners)
            {
                for (var t = 0; t < _count; t++)
                {
                    var l = lp + (LinearStride * t);
                    int i0 = 3 * corners[3 * t], i1 = 3 * corners[(3 * t) + 1], i2 = 3 * corners[(3 * t) + 2];
                    double nx = l[0], ny = l[1], nz = l[2];
                    var along = (nx * (wp[i0] + wp[i1] + wp[i2])) + (ny * (wp[i0 + 1] + wp[i1 + 1] + wp[i2 + 1])) + (nz * (wp[i0 + 2] + wp[i1 + 2] + wp[i2 + 2]));
                    var c = l[3] * along;
                    double dx = c * nx, dy = c * ny, dz = c * nz;
                    rp[i0] -= dx;
                    rp[i0 + 1] -= dy;
                    rp[i0 + 2] -= dz;
                    rp[i1] -= dx;
                    rp[i1 + 1] -= dy;
                    rp[i1 + 2] -= dz;
                    rp[i2] -= dx;
                    rp[i2 + 1] -= dy;
                    rp[i2 + 2] -= dz;
                }
            }
        }
    }

    /// <inheritdoc />
    public void AddDiagonalBlocks(Span<double> blocks)
    {
        _linearized.Check(nameof(TriangleAerodynamics), _count, 0);
        Span<double> block = stackalloc double[9];
        for (var t = 0; t < _count; t++)
        {
            Block(t, block);
            for (var a = 0; a < 3; a++)
            {
                var o = 9 * _corners[(3 * t) + a];
                for (var k = 0; k < 9; k++)
                {
                    blocks[o + k] += block[k];
                }
            }
        }
    }

    /// <inheritdoc />
    /// <remarks>Three per triangle, its edges: (0, 1), (1, 2), (2, 0).</remarks>
    public int CouplingCount => 3 * _count;

    /// <inheritdoc />
    public void WriteCouplings(Span<int> first, Span<int> second)
    {
        for (var t = 0; t < _count; t++)
        {
            for (var e = 0; e < 3; e++)
            {
                first[(3 * t) + e] = _corners[(3 * t) + e];
                second[(3 * t) + e] = _corners[(3 * t) + ((e + 1) % 3)];
            }
        }
    }

    /// <inheritdoc />
    public void AddCouplingBlocks(Span<double> destination, ReadOnlySpan<int> forwardBlock, ReadOnlySpan<int> backwardBlock)
    {
        _linearized.Check(nameof(TriangleAerodynamics), _count, 0);
        var forward = forwardBlock.ForReading();
        var backward = backwardBlock.ForReading();
        Span<double> block = stackalloc double[9];
        for (var t = 0; t < _count; t++)
        {
            Block(t, block);
            for (var e = 0; e < 3; e++)
            {
                // The block is symmetric: J_ji = J_ij^T = J_ij.
                var c = (3 * t) + e;
                if (forward[c] >= 0)
                {
                    Add(destination, 9 * forward[c], block);
                }

                if (backward[c] >= 0)
                {
                    Add(destination, 9 * backward[c], block);
                }
            }
        }
    }

    private static void Add(Span<double> destination, int offset, Span<double> block)
    {
        for (var k = 0; k < 9; k++)
        {
            destination[offset + k] += block[k];
        }
    }

    /// <summary>-K n n^T of triangle t, row-major: every one of its nine corner-pair blocks.</summary>
    private void Block(int t, Span<double> block)
    {
        var o = LinearStride * t;
        double nx = _linear[o], ny = _linear[o + 1], nz = _linear[o + 2], k = _linear[o + 3];
        block[0] = -k * nx * nx;
        block[1] = -k * nx * ny;
        block[2] = -k * nx * nz;
        block[3] = block[1];
        block[4] = -k * ny * ny;
        block[5] = -k * ny * nz;
        block[6] = block[2];
        block[7] = block[5];
        block[8] = -k * nz * nz;
    }

    private void CheckSizes(int positions, int velocities, int result)
    {
        var needed = 3 * _system.Count;
        if (positions < needed || velocities < needed || result < needed)
        {
            throw new ArgumentException(
                $"TriangleAerodynamics needs buffers of {needed} values (3 per particle of its system); got {positions}, {velocities} and {result}.");
        }
    }
}
