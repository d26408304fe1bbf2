using System;

namespace ParticlePhysics.Numerics;

/// <summary>e^x - 1 without the cancellation of Math.Exp(x) - 1 near x = 0 (netstandard2.1 has no Math.Expm1).</summary>
internal static class ExpMinusOne
{
    /// <summary>
    /// Kahan's method: with u = exp(x) rounded, (u - 1) x / ln(u) cancels the rounding error of u to first order,
    /// giving e^x - 1 to a few ulps for every x.
    /// </summary>
    public static double Of(double x)
    {
        var u = Math.Exp(x);
        if (u == 1.0)
        {
            return x;
        }

        if (double.IsPositiveInfinity(u))
        {
            return u;
        }

        var um1 = u - 1.0;
        return um1 == -1.0 ? -1.0 : um1 * x / Math.Log(u);
    }
}
