using System;
using System.Runtime.CompilerServices;

namespace ParticlePhysics.Fluids;

/// <summary>
/// The two smoothing kernels of position-based fluids (Müller, Charypar and Gross 2003; Macklin and Müller 2013) for a
/// smoothing radius h: poly6 for densities, W(r) = 315 / (64 pi h^9) (h^2 - r^2)^3, and the gradient of spiky for
/// the constraint gradients, grad W(r) = -45 / (pi h^6) (h - r)^2 r / |r|, both 0 from r = h on.
/// </summary>
/// <remarks>
/// Each integrates to 1 over its ball (poly6: 4 pi int_0^h r^2 (h^2 - r^2)^3 dr = 64 pi h^9 / 315; spiky,
/// 15 / (pi h^6) (h - r)^3: 4 pi int_0^h r^2 (h - r)^3 dr = pi h^6 / 15). Spiky's gradient does not vanish as r goes
/// to 0, unlike poly6's, so two particles pushed together keep being pushed apart. Only + - * / are used.
/// </remarks>
public readonly struct SphKernel
{
    private readonly double _h2;
    private readonly double _poly6;
    private readonly double _spiky;

    /// <summary>The kernels of smoothing radius <paramref name="radius"/> (m).</summary>
    /// <exception cref="ArgumentOutOfRangeException">The radius is not positive and finite, or its kernels are not finite.</exception>
    public SphKernel(double radius)
    {
        Guard.PositiveFinite(radius, nameof(radius));
        Radius = radius;
        _h2 = radius * radius;
        var h3 = _h2 * radius;
        var h6 = h3 * h3;
        _poly6 = 315.0 / (64.0 * Math.PI * h6 * h3);
        _spiky = 45.0 / (Math.PI * h6);
        if (double.IsInfinity(_poly6) || double.IsInfinity(_spiky) || _poly6 == 0.0)
        {
            throw new ArgumentOutOfRangeException(nameof(radius), radius, $"a smoothing radius of {Guard.Format(radius)} m gives kernels that are not finite.");
        }
    }

    /// <summary>The smoothing radius h, m.</summary>
    public double Radius { get; }

    /// <summary>poly6 at distance 0: 315 / (64 pi h^3), 1/m^3.</summary>
    public double Peak => _poly6 * _h2 * _h2 * _h2;

    /// <summary>poly6 at squared distance <paramref name="r2"/> (m^2), 1/m^3.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public double Density(double r2)
    {
        if (r2 >= _h2)
        {
            return 0.0;
        }

        var d = _h2 - r2;
        return _poly6 * d * d * d;
    }

    /// <summary>
    /// The spiky gradient's magnitude over the distance at distance <paramref name="r"/> (m): grad W = -factor * r_vec,
    /// so factor = 45 / (pi h^6) (h - r)^2 / r, 1/m^5; 0 at r = 0 (no direction) and from h on.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public double GradientOverDistance(double r)
    {
        if (r >= Radius || r <= 0.0)
        {
            return 0.0;
        }

        var d = Radius - r;
        return _spiky * d * d / r;
    }
}
