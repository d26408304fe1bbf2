using System;
using ParticlePhysics.Internal;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Forces;

/// <summary>
/// Constant-strain triangles of a membrane: Green strain and the linear Saint Venant-Kirchhoff law of plane stress,
/// with Kelvin-Voigt damping. Per triangle of rest area A0, with Dm^-1 = [[p, q], [r, s]] the inverse of its rest edges
/// in a frame of its own plane: F = (x1 - x0) (p, q) + (x2 - x0) (r, s) (3 x 2, columns F1, F2), E = (F^T F - I) / 2,
/// S = 2 mu E + lambda tr(E) I + tau (2 mu E' + lambda tr(E') I), P = F S, and the corner forces
/// f1 = -A0 (p P1 + q P2), f2 = -A0 (r P1 + s P2), f0 = -f1 - f2. Energy A0 (mu E:E + lambda tr(E)^2 / 2).
/// </summary>
/// <remarks>
/// <para>
/// Material: Y = Young's modulus times thickness (N/m) and Poisson's ratio nu, 0 &lt;= nu &lt; 1/2; plane stress gives
/// mu = Y / (2 (1 + nu)) and lambda = Y nu / (1 - nu^2), so that a strip of width b pulled by a force F along its length
/// stretches by F / (Y b) per unit length to first order. Damping: the viscosity eta (N s/m) of the same law applied to
/// the strain rate E' = sym(F^T F'), tau = eta / Y: every strain mode decays at the rate its stiffness sets.
/// </para>
/// <para>
/// Jacobian (for implicit Euler), per triangle and corners i, j with beta_0 = -(p + r, q + s), beta_1 = (p, q),
/// beta_2 = (r, s): df_i/dx_j = -A0 [mu (beta_i . beta_j) F F^T + mu (F beta_j)(F beta_i)^T + lambda (F beta_i)(F beta_j)^T
/// + (beta_i^T S+ beta_j) I] and df_i/dv_j the first three terms times tau. The material part is G^T C G, positive
/// semi-definite; the geometric part takes S+, the stress with its compressive eigenvalue dropped (as a compressed
/// spring drops its transverse stiffness), so that M - h^2 J stays positive definite; the position derivative of the
/// damping is left out, as the springs leave theirs. The product is computed from F, S+ and two scalars per triangle
/// (about 90 flops), and the couplings are the triangles' three edges.
/// </para>
/// </remarks>
public sealed class TriangleMembrane : IForceGenerator, IPotentialEnergy, IBoundForce, IJacobianCouplings, IAppendOnlyCouplings, IMembraneElements
{
    private const int Stride = 8; // p, q, r, s, A0, mu, lambda, tau
    private const int LinearStride = 11; // F1 (3), F2 (3), a A0 S+ (3), c 2 mu, c lambda with c = (a + b tau) A0

    // The smallest rest area, relative to the square of the longest edge, of a triangle that is not degenerate.
    private const double MinRelativeArea = 1e-12;

    private readonly ParticleWorld _system;
    private int[] _corners = Array.Empty<int>();
    private double[] _parameters = Array.Empty<double>();
    private double[] _linear = Array.Empty<double>();
    private int _count;
    private int _topologyVersion;
    private int _parameterVersion;
    private LinearizationStamp _linearized;

    /// <summary>An empty membrane for the particles of <paramref name="system"/>.</summary>
    public TriangleMembrane(ParticleWorld system)
    {
        Guard.NotNull(system, nameof(system));
        _system = system;
    }

    /// <summary>The number of triangles.</summary>
    public int Count => _count;

    /// <inheritdoc />
    int IMembraneElements.TriangleCount => _count;

    /// <inheritdoc />
    public int TopologyVersion => _topologyVersion;

    /// <inheritdoc />
    public int ParameterVersion => _parameterVersion;

    object? IBoundForce.World => _system;

    /// <summary>
    /// Adds a triangle of three distinct existing particles, at rest in the shape of <paramref name="rest0"/>,
    /// <paramref name="rest1"/>, <paramref name="rest2"/> (any position and orientation).
    /// </summary>
    /// <param name="first">Corner 0.</param>
    /// <param name="second">Corner 1.</param>
    /// <param name="third">Corner 2.</param>
    /// <param name="rest0">Corner 0's rest position, m.</param>
    /// <param name="rest1">Corner 1's rest position, m.</param>
    /// <param name="rest2">Corner 2's rest position, m.</param>
    /// <param name="modulus">Y, Young's modulus times thickness, N/m: positive and finite.</param>
    /// <param name="poisson">nu, from 0 to less than 1/2.</param>
    /// <param name="damping">eta, the viscosity of the strain rate, N s/m: finite and &gt;= 0.</param>
    /// <returns>The triangle's index.</returns>
    /// <exception cref="ArgumentException">The rest triangle is degenerate (area at most 1e-12 of its longest edge squared).</exception>
    public int Add(
        int first, int second, int third, Vector3d rest0, Vector3d rest1, Vector3d rest2, double modulus, double poisson, double damping = 0.0)
    {
        _system.ThrowIfStepping();
        Guard.ParticleIndex(first, _system.Count, nameof(first));
        Guard.ParticleIndex(second, _system.Count, nameof(second));
        Guard.ParticleIndex(third, _system.Count, nameof(third));
        Guard.DistinctParticles(first, second, nameof(second));
        Guard.DistinctParticles(first, third, nameof(third));
        Guard.DistinctParticles(second, third, nameof(third));
        Guard.Finite(rest0, nameof(rest0));
        Guard.Finite(rest1, nameof(rest1));
        Guard.Finite(rest2, nameof(rest2));
        var material = Material(modulus, poisson, damping);
        Span<double> p = stackalloc double[Stride];
        RestShape(rest0, rest1, rest2, p);
        material.CopyTo(p.Slice(5));
        if (_count == _parameters.Length / Stride)
        {
            var capacity = Math.Max(8, 2 * _count);
            Array.Resize(ref _corners, 3 * capacity);
            Array.Resize(ref _parameters, Stride * capacity);
        }

        _corners[3 * _count] = first;
        _corners[(3 * _count) + 1] = second;
        _corners[(3 * _count) + 2] = third;
        p.CopyTo(_parameters.AsSpan(Stride * _count, Stride));
        _topologyVersion++;
        return _count++;
    }

    /// <summary>Adds a triangle at rest in the shape its particles have now.</summary>
    /// <returns>The triangle's index.</returns>
    public int Add(int first, int second, int third, double modulus, double poisson, double damping = 0.0)
    {
        Guard.ParticleIndex(first, _system.Count, nameof(first));
        Guard.ParticleIndex(second, _system.Count, nameof(second));
        Guard.ParticleIndex(third, _system.Count, nameof(third));
        return Add(first, second, third, _system.GetPosition(first), _system.GetPosition(second), _system.GetPosition(third), modulus, poisson, damping);
    }

    /// <summary>The three corners of a triangle.</summary>
    public (int First, int Second, int Third) GetCorners(int triangle)
    {
        CheckTriangle(triangle);
        return (_corners[3 * triangle], _corners[(3 * triangle) + 1], _corners[(3 * triangle) + 2]);
    }

    /// <summary>The rest area A0 of a triangle, m^2.</summary>
    public double GetRestArea(int triangle)
    {
        CheckTriangle(triangle);
        return _parameters[(Stride * triangle) + 4];
    }

    /// <summary>Gives every triangle a new material (the rest shapes stay).</summary>
    /// <param name="modulus">Y, N/m: positive and finite.</param>
    /// <param name="poisson">nu, from 0 to less than 1/2.</param>
    /// <param name="damping">eta, N s/m: finite and &gt;= 0.</param>
    public void SetMaterial(double modulus, double poisson, double damping)
    {
        _system.ThrowIfStepping();
        var material = Material(modulus, poisson, damping);
        for (var t = 0; t < _count; t++)
        {
            material.CopyTo(_parameters.AsSpan((Stride * t) + 5, 3));
        }

        _parameterVersion++;
    }

    /// <inheritdoc />
    public void CopyTriangles(Span<int> corners, Span<double> parameters)
    {
        _corners.AsSpan(0, 3 * _count).CopyTo(corners);
        _parameters.AsSpan(0, Stride * _count).CopyTo(parameters);
    }

    /// <summary>mu, lambda and tau of (Y, nu, eta), checked.</summary>
    private static double[] Material(double modulus, double poisson, double damping)
    {
        Guard.PositiveFinite(modulus, nameof(modulus));
        if (!(poisson >= 0.0 && poisson < 0.5))
        {
            throw new ArgumentOutOfRangeException(
                nameof(poisson), poisson, $"poisson (nu) must be from 0 to less than 0.5; got {Guard.Format(poisson)}.");
        }

        Guard.NonNegativeFinite(damping, nameof(damping));
        var tau = damping / modulus;
        Guard.Finite(tau, nameof(damping));
        return new[] { modulus / (2.0 * (1.0 + poisson)), modulus * poisson / (1.0 - (poisson * poisson)), tau };
    }

    /// <summary>
    /// Dm^-1 and A0 of a rest triangle: in the frame u = e1 / |e1|, w = the unit part of e2 normal to u, the rest edges
    /// are e1 = (|e1|, 0) and e2 = (e2 . u, 2 A0 / |e1|), and Dm^-1 = [[1 / |e1|, -(e2 . u) / (|e1| h)], [0, 1 / h]]
    /// with h = 2 A0 / |e1| (rows: the weights of e1 and e2 in F's two columns).
    /// </summary>
    private static void RestShape(Vector3d rest0, Vector3d rest1, Vector3d rest2, Span<double> p)
    {
        var e1 = rest1 - rest0;
        var e2 = rest2 - rest0;
        var longest = Math.Max(e1.LengthSquared, Math.Max(e2.LengthSquared, (rest2 - rest1).LengthSquared));
        var twiceArea = Vector3d.Cross(e1, e2).Length;
        var length = e1.Length;
        if (!(twiceArea > 2.0 * MinRelativeArea * longest) || !DoubleChecks.IsFinite(twiceArea) || !DoubleChecks.IsFinite(longest))
        {
            throw new ArgumentException(
                $"The rest triangle {rest0}, {rest1}, {rest2} is degenerate (area {Guard.Format(0.5 * twiceArea)} m^2): "
                + "its corners must not lie on one line.");
        }

        var along = Vector3d.Dot(e2, e1) / length;
        var height = twiceArea / length;
        p[0] = 1.0 / length;
        p[1] = -along / (length * height);
        p[2] = 0.0;
        p[3] = 1.0 / height;
        p[4] = 0.5 * twiceArea;
    }

    /// <inheritdoc />
    public void AddForces(in ParticleState state, Span<double> forces)
    {
        CheckSizes(state.Positions.Length, state.Velocities.Length, forces.Length);
        var x = state.Positions.ForReading();
        var v = state.Velocities.ForReading();
        for (var t = 0; t < _count; t++)
        {
            int i0 = 3 * _corners[3 * t], i1 = 3 * _corners[(3 * t) + 1], i2 = 3 * _corners[(3 * t) + 2];
            var o = Stride * t;
            double p = _parameters[o], q = _parameters[o + 1], r = _parameters[o + 2], s = _parameters[o + 3];
            double area = _parameters[o + 4], mu = _parameters[o + 5], lambda = _parameters[o + 6], tau = _parameters[o + 7];

            // F and F' (the rate), column by column.
            double ax = x[i1] - x[i0], ay = x[i1 + 1] - x[i0 + 1], az = x[i1 + 2] - x[i0 + 2];
            double bx = x[i2] - x[i0], by = x[i2 + 1] - x[i0 + 1], bz = x[i2 + 2] - x[i0 + 2];
            double f1x = (p * ax) + (r * bx), f1y = (p * ay) + (r * by), f1z = (p * az) + (r * bz);
            double f2x = (q * ax) + (s * bx), f2y = (q * ay) + (s * by), f2z = (q * az) + (s * bz);
            double exx = 0.5 * ((f1x * f1x) + (f1y * f1y) + (f1z * f1z) - 1.0);
            double eyy = 0.5 * ((f2x * f2x) + (f2y * f2y) + (f2z * f2z) - 1.0);
            var exy = 0.5 * ((f1x * f2x) + (f1y * f2y) + (f1z * f2z));
            if (tau != 0.0)
            {
                double ux = v[i1] - v[i0], uy = v[i1 + 1] - v[i0 + 1], uz = v[i1 + 2] - v[i0 + 2];
                double wx = v[i2] - v[i0], wy = v[i2 + 1] - v[i0 + 1], wz = v[i2 + 2] - v[i0 + 2];
                double g1x = (p * ux) + (r * wx), g1y = (p * uy) + (r * wy), g1z = (p * uz) + (r * wz);
                double g2x = (q * ux) + (s * wx), g2y = (q * uy) + (s * wy), g2z = (q * uz) + (s * wz);
                exx += tau * ((f1x * g1x) + (f1y * g1y) + (f1z * g1z));
                eyy += tau * ((f2x * g2x) + (f2y * g2y) + (f2z * g2z));
                exy += tau * 0.5 * ((f1x * g2x) + (f1y * g2y) + (f1z * g2z) + (f2x * g1x) + (f2y * g1y) + (f2z * g1z));
            }

            // S (with the damping's share) times A0, then P = F S.
            var trace = lambda * (exx + eyy);
            var sxx = area * ((2.0 * mu * exx) + trace);
            var syy = area * ((2.0 * mu * eyy) + trace);
            var sxy = area * 2.0 * mu * exy;
            double p1x = (f1x * sxx) + (f2x * sxy), p1y = (f1y * sxx) + (f2y * sxy), p1z = (f1z * sxx) + (f2z * sxy);
            double p2x = (f1x * sxy) + (f2x * syy), p2y = (f1y * sxy) + (f2y * syy), p2z = (f1z * sxy) + (f2z * syy);
            double c1x = (p * p1x) + (q * p2x), c1y = (p * p1y) + (q * p2y), c1z = (p * p1z) + (q * p2z);
            double c2x = (r * p1x) + (s * p2x), c2y = (r * p1y) + (s * p2y), c2z = (r * p1z) + (s * p2z);
            forces[i1] -= c1x;
            forces[i1 + 1] -= c1y;
            forces[i1 + 2] -= c1z;
            forces[i2] -= c2x;
            forces[i2 + 1] -= c2y;
            forces[i2 + 2] -= c2z;
            forces[i0] += c1x + c2x;
            forces[i0 + 1] += c1y + c2y;
            forces[i0 + 2] += c1z + c2z;
        }
    }

    /// <inheritdoc />
    public double PotentialEnergy(in ParticleState state)
    {
        CheckSizes(state.Positions.Length, state.Positions.Length, state.Positions.Length);
        var x = state.Positions.ForReading();
        var sum = 0.0;
        for (var t = 0; t < _count; t++)
        {
            var (exx, eyy, exy) = Strain(x, t);
            var o = Stride * t;
            double mu = _parameters[o + 5], lambda = _parameters[o + 6];
            var trace = exx + eyy;
            sum += _parameters[o + 4] * ((mu * ((exx * exx) + (eyy * eyy) + (2.0 * exy * exy))) + (0.5 * lambda * trace * trace));
        }

        return sum;
    }

    /// <summary>The Green strain (E_xx, E_yy, E_xy) of triangle <paramref name="triangle"/> at the given positions.</summary>
    public (double Exx, double Eyy, double Exy) GetStrain(ReadOnlySpan<double> positions, int triangle)
    {
        CheckTriangle(triangle);
        CheckSizes(positions.Length, positions.Length, positions.Length);
        return Strain(positions.ForReading(), triangle);
    }

    private (double, double, double) Strain(Span<double> x, int t)
    {
        int i0 = 3 * _corners[3 * t], i1 = 3 * _corners[(3 * t) + 1], i2 = 3 * _corners[(3 * t) + 2];
        var o = Stride * t;
        double p = _parameters[o], q = _parameters[o + 1], r = _parameters[o + 2], s = _parameters[o + 3];
        double ax = x[i1] - x[i0], ay = x[i1 + 1] - x[i0 + 1], az = x[i1 + 2] - x[i0 + 2];
        double bx = x[i2] - x[i0], by = x[i2 + 1] - x[i0 + 1], bz = x[i2 + 2] - x[i0 + 2];
        double f1x = (p * ax) + (r * bx), f1y = (p * ay) + (r * by), f1z = (p * az) + (r * bz);
        double f2x = (q * ax) + (s * bx), f2y = (q * ay) + (s * by), f2z = (q * az) + (s * bz);
        return (
            0.5 * ((f1x * f1x) + (f1y * f1y) + (f1z * f1z) - 1.0),
            0.5 * ((f2x * f2x) + (f2y * f2y) + (f2z * f2z) - 1.0),
            0.5 * ((f1x * f2x) + (f1y * f2y) + (f1z * f2z)));
    }

    /// <inheritdoc />
    public void Linearize(
        in ParticleState state, double positionScale, double velocityScale, Span<double> positionJacobianTimesVelocity)
    {
        CheckSizes(state.Positions.Length, state.Velocities.Length, positionJacobianTimesVelocity.Length);
        if (_linear.Length < LinearStride * _count)
        {
            _linear = new double[LinearStride * _parameters.Length / Stride];
        }

        var x = state.Positions.ForReading();
        var v = state.Velocities.ForReading();
        for (var t = 0; t < _count; t++)
        {
            int i0 = 3 * _corners[3 * t], i1 = 3 * _corners[(3 * t) + 1], i2 = 3 * _corners[(3 * t) + 2];
            var o = Stride * t;
            double p = _parameters[o], q = _parameters[o + 1], r = _parameters[o + 2], s = _parameters[o + 3];
            double area = _parameters[o + 4], mu = _parameters[o + 5], lambda = _parameters[o + 6], tau = _parameters[o + 7];
            double ax = x[i1] - x[i0], ay = x[i1 + 1] - x[i0 + 1], az = x[i1 + 2] - x[i0 + 2];
            double bx = x[i2] - x[i0], by = x[i2 + 1] - x[i0 + 1], bz = x[i2 + 2] - x[i0 + 2];
            var l = _linear.AsSpan(LinearStride * t, LinearStride);
            l[0] = (p * ax) + (r * bx);
            l[1] = (p * ay) + (r * by);
            l[2] = (p * az) + (r * bz);
            l[3] = (q * ax) + (s * bx);
            l[4] = (q * ay) + (s * by);
            l[5] = (q * az) + (s * bz);
            var exx = 0.5 * ((l[0] * l[0]) + (l[1] * l[1]) + (l[2] * l[2]) - 1.0);
            var eyy = 0.5 * ((l[3] * l[3]) + (l[4] * l[4]) + (l[5] * l[5]) - 1.0);
            var exy = 0.5 * ((l[0] * l[3]) + (l[1] * l[4]) + (l[2] * l[5]));
            var trace = lambda * (exx + eyy);
            var (sxx, syy, sxy) = PositivePart((2.0 * mu * exx) + trace, (2.0 * mu * eyy) + trace, 2.0 * mu * exy);

            // (df/dx) v first, with the position Jacobian alone (a = 1, b = 0), then the step's J = a df/dx + b df/dv.
            l[6] = area * sxx;
            l[7] = area * syy;
            l[8] = area * sxy;
            l[9] = area * 2.0 * mu;
            l[10] = area * lambda;
            Product(l, v, positionJacobianTimesVelocity, i0, i1, i2, p, q, r, s);
            l[6] *= positionScale;
            l[7] *= positionScale;
            l[8] *= positionScale;
            var c = positionScale + (velocityScale * tau);
            l[9] *= c;
            l[10] *= c;
        }

        _linearized.Record(_count, 0);
    }

    /// <summary>
    /// The part of a symmetric 2 x 2 matrix on its non-negative eigenvalues: S itself when both are &gt;= 0, 0 when
    /// both are &lt;= 0, else l+ (S - l- I) / (l+ - l-), the projector on the positive eigenvector scaled by l+.
    /// </summary>
    private static (double Xx, double Yy, double Xy) PositivePart(double xx, double yy, double xy)
    {
        var mean = 0.5 * (xx + yy);
        var half = 0.5 * (xx - yy);
        var radius = Math.Sqrt((half * half) + (xy * xy));
        double high = mean + radius, low = mean - radius;
        if (low >= 0.0)
        {
            return (xx, yy, xy);
        }

        if (high <= 0.0)
        {
            return (0.0, 0.0, 0.0);
        }

        var scale = high / (high - low);
        return (scale * (xx - low), scale * (yy - low), scale * xy);
    }

    /// <inheritdoc />
    public void AddJacobianProduct(ReadOnlySpan<double> w, Span<double> result)
    {
        _linearized.Check(nameof(TriangleMembrane), _count, 0);
        CheckSizes(w.Length, w.Length, result.Length);
        var wr = w.ForReading();
        for (var t = 0; t < _count; t++)
        {
            var o = Stride * t;
            Product(
                _linear.AsSpan(LinearStride * t, LinearStride),
                wr,
                result,
                3 * _corners[3 * t],
                3 * _corners[(3 * t) + 1],
                3 * _corners[(3 * t) + 2],
                _parameters[o],
                _parameters[o + 1],
                _parameters[o + 2],
                _parameters[o + 3]);
        }
    }

    /// <summary>
    /// result += K w for one triangle: dF from w, dE = sym(F^T dF), dS = 2 mu dE + lambda tr(dE) I (scaled), then
    /// dP = F dS + dF S+ and the corners' -A0 dP Dm^-T (A0 and the scales are in l).
    /// </summary>
    private static void Product(Span<double> l, Span<double> w, Span<double> result, int i0, int i1, int i2, double p, double q, double r, double s)
    {
        double ax = w[i1] - w[i0], ay = w[i1 + 1] - w[i0 + 1], az = w[i1 + 2] - w[i0 + 2];
        double bx = w[i2] - w[i0], by = w[i2 + 1] - w[i0 + 1], bz = w[i2 + 2] - w[i0 + 2];
        double d1x = (p * ax) + (r * bx), d1y = (p * ay) + (r * by), d1z = (p * az) + (r * bz);
        double d2x = (q * ax) + (s * bx), d2y = (q * ay) + (s * by), d2z = (q * az) + (s * bz);
        double f1x = l[0], f1y = l[1], f1z = l[2], f2x = l[3], f2y = l[4], f2z = l[5];
        var exx = (f1x * d1x) + (f1y * d1y) + (f1z * d1z);
        var eyy = (f2x * d2x) + (f2y * d2y) + (f2z * d2z);
        var exy = 0.5 * ((f1x * d2x) + (f1y * d2y) + (f1z * d2z) + (f2x * d1x) + (f2y * d1y) + (f2z * d1z));
        var trace = l[10] * (exx + eyy);
        var sxx = (l[9] * exx) + trace;
        var syy = (l[9] * eyy) + trace;
        var sxy = l[9] * exy;
        double gxx = l[6], gyy = l[7], gxy = l[8];
        var p1x = (f1x * sxx) + (f2x * sxy) + (d1x * gxx) + (d2x * gxy);
        var p1y = (f1y * sxx) + (f2y * sxy) + (d1y * gxx) + (d2y * gxy);
        var p1z = (f1z * sxx) + (f2z * sxy) + (d1z * gxx) + (d2z * gxy);
        var p2x = (f1x * sxy) + (f2x * syy) + (d1x * gxy) + (d2x * gyy);
        var p2y = (f1y * sxy) + (f2y * syy) + (d1y * gxy) + (d2y * gyy);
        var p2z = (f1z * sxy) + (f2z * syy) + (d1z * gxy) + (d2z * gyy);
        double c1x = (p * p1x) + (q * p2x), c1y = (p * p1y) + (q * p2y), c1z = (p * p1z) + (q * p2z);
        double c2x = (r * p1x) + (s * p2x), c2y = (r * p1y) + (s * p2y), c2z = (r * p1z) + (s * p2z);
        result[i1] -= c1x;
        result[i1 + 1] -= c1y;
        result[i1 + 2] -= c1z;
        result[i2] -= c2x;
        result[i2 + 1] -= c2y;
        result[i2 + 2] -= c2z;
        result[i0] += c1x + c2x;
        result[i0 + 1] += c1y + c2y;
        result[i0 + 2] += c1z + c2z;
    }

    /// <inheritdoc />
    public void AddDiagonalBlocks(Span<double> blocks)
    {
        _linearized.Check(nameof(TriangleMembrane), _count, 0);
        Span<double> block = stackalloc double[9];
        for (var t = 0; t < _count; t++)
        {
            for (var a = 0; a < 3; a++)
            {
                Block(t, a, a, block);
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
        _linearized.Check(nameof(TriangleMembrane), _count, 0);
        var forward = forwardBlock.ForReading();
        var backward = backwardBlock.ForReading();
        Span<double> block = stackalloc double[9];
        for (var t = 0; t < _count; t++)
        {
            for (var e = 0; e < 3; e++)
            {
                var c = (3 * t) + e;
                if (forward[c] < 0 && backward[c] < 0)
                {
                    continue;
                }

                Block(t, e, (e + 1) % 3, block);
                if (forward[c] >= 0)
                {
                    var o = 9 * forward[c];
                    for (var k = 0; k < 9; k++)
                    {
                        destination[o + k] += block[k];
                    }
                }

                if (backward[c] >= 0)
                {
                    var o = 9 * backward[c];
                    for (var row = 0; row < 3; row++)
                    {
                        for (var col = 0; col < 3; col++)
                        {
                            destination[o + (3 * row) + col] += block[(3 * col) + row];
                        }
                    }
                }
            }
        }
    }

    /// <summary>
    /// The block J_ij = d f_i / d x_j of triangle t's corners i and j (row-major), from the linearisation:
    /// -[mu' (b_i . b_j) F F^T + mu' (F b_j)(F b_i)^T + lambda' (F b_i)(F b_j)^T + (b_i^T S' b_j) I], where mu', lambda'
    /// and S' carry A0 and the step's scales.
    /// </summary>
    private void Block(int t, int i, int j, Span<double> block)
    {
        var o = Stride * t;
        double p = _parameters[o], q = _parameters[o + 1], r = _parameters[o + 2], s = _parameters[o + 3];
        var l = _linear.AsSpan(LinearStride * t, LinearStride);
        var (bix, biy) = Beta(i, p, q, r, s);
        var (bjx, bjy) = Beta(j, p, q, r, s);
        double mu = 0.5 * l[9], lambda = l[10];
        double f1x = l[0], f1y = l[1], f1z = l[2], f2x = l[3], f2y = l[4], f2z = l[5];
        double gix = (f1x * bix) + (f2x * biy), giy = (f1y * bix) + (f2y * biy), giz = (f1z * bix) + (f2z * biy);
        double gjx = (f1x * bjx) + (f2x * bjy), gjy = (f1y * bjx) + (f2y * bjy), gjz = (f1z * bjx) + (f2z * bjy);
        var along = mu * ((bix * bjx) + (biy * bjy));
        var geometric = (bix * ((l[6] * bjx) + (l[8] * bjy))) + (biy * ((l[8] * bjx) + (l[7] * bjy)));
        Span<double> fi = stackalloc double[] { f1x, f1y, f1z };
        Span<double> fj = stackalloc double[] { f2x, f2y, f2z };
        Span<double> gi = stackalloc double[] { gix, giy, giz };
        Span<double> gj = stackalloc double[] { gjx, gjy, gjz };
        for (var row = 0; row < 3; row++)
        {
            for (var col = 0; col < 3; col++)
            {
                var value = (along * ((fi[row] * fi[col]) + (fj[row] * fj[col])))
                    + (mu * gj[row] * gi[col])
                    + (lambda * gi[row] * gj[col]);
                if (row == col)
                {
                    value += geometric;
                }

                block[(3 * row) + col] = -value;
            }
        }
    }

    private static (double X, double Y) Beta(int corner, double p, double q, double r, double s) => corner switch
    {
        0 => (-(p + r), -(q + s)),
        1 => (p, q),
        _ => (r, s),
    };

    private void CheckTriangle(int triangle)
    {
        if ((uint)triangle >= (uint)_count)
        {
            throw new ArgumentOutOfRangeException(
                nameof(triangle), triangle, $"triangle must name an existing triangle, 0 to {_count - 1}; got {triangle}.");
        }
    }

    private void CheckSizes(int positions, int velocities, int result)
    {
        var needed = 3 * _system.Count;
        if (positions < needed || velocities < needed || result < needed)
        {
            throw new ArgumentException(
                $"TriangleMembrane needs buffers of {needed} values (3 per particle of its system); got {positions}, {velocities} and {result}.");
        }
    }
}
