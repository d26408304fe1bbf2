using System;
using System.Runtime.CompilerServices;

namespace ParticlePhysics.Fluids;

/// <summary>
/// The smoothing kernel of the fluid for a smoothing radius h: spiky (Müller, Charypar and Gross 2003),
/// W(r) = 15 / (pi h^6) (h - r)^3, 0 from r = h on, and its exact gradient grad W = -45 / (pi h^6) (h - r)^2 r / |r|.
/// </summary>
/// <remarks>
/// <para>
/// W integrates to 1 over its ball (4 pi int_0^h r^2 (h - r)^3 dr = pi h^6 / 15), and its gradient does not vanish as
/// r goes to 0, so two particles pushed together keep being pushed apart (poly6's does, and lets particles clump).
/// </para>
/// <para>
/// Macklin and Müller take densities with poly6 and gradients with spiky. The projection then moves particles along a
/// gradient that is not the density's, and some patterns of displacement grow at every projection: on the rest lattice
/// at h = 2 s, a Jacobi projection scales the displacement wave of wavevector k by 1 - mu(k) with
/// mu(k) = G_W(k) . G_grad(k) / sum_b |grad W_b|^2, G(k) = sum_b grad W_b sin(k . x_b), and with the two kernels mu
/// goes down to -0.026 (at k s = (pi, pi, pi / 2)): the fluid boils, the more so the more substeps. With one kernel
/// for both, mu(k) = |G(k)|^2 / sum_b |grad W_b|^2 &gt;= 0 for every k, at most 2.82 for spiky (hence the default
/// relaxation, <see cref="PositionBasedFluid.Relaxation"/>). Only + - * / and sqrt are used.
/// </para>
/// </remarks>
public readonly struct SphKernel
{
    private readonly double _spiky;

    /// <summary>The kernel of smoothing radius <paramref name="radius"/> (m).</summary>
    /// <exception cref="ArgumentOutOfRangeException">The radius is not positive and finite, or its kernel is not finite.</exception>
    public SphKernel(double radius)
    {
        Guard.PositiveFinite(radius, nameof(radius));
        Radius = radius;
        var h3 = radius * radius * radius;
        _spiky = 15.0 / (Math.PI * h3 * h3);
        if (double.IsInfinity(_spiky) || _spiky == 0.0 || double.IsInfinity(_spiky * h3))
        {
            throw new ArgumentOutOfRangeException(nameof(radius), radius, $"a smoothing radius of {Guard.Format(radius)} m gives a kernel that is not finite.");
        }
    }

    /// <summary>The smoothing radius h, m.</summary>
    public double Radius { get; }

    /// <summary>W at distance 0: 15 / (pi h^3), 1/m^3.</summary>
    public double Peak => _spiky * Radius * Radius * Radius;

    /// <summary>W at distance <paramref name="r"/> (m), 1/m^3.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public double Density(double r)
    {
        if (r >= Radius)
        {
            return 0.0;
        }

        var d = Radius - r;
        return _spiky * d * d * d;
    }

    /// <summary>
    /// The gradient's magnitude over the distance at distance <paramref name="r"/> (m): grad W = -factor * r_vec, so
    /// factor = 45 / (pi h^6) (h - r)^2 / r, 1/m^5; 0 at r = 0 (no direction) and from h on.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public double GradientOverDistance(double r)
    {
        if (r >= Radius || r <= 0.0)
        {
            return 0.0;
        }

        var d = Radius - r;
        return 3.0 * _spiky * d * d / r;
    }
}
