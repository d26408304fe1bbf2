using System;

namespace ParticlePhysics.Numerics;

/// <summary>
/// The root of a continuous, strictly monotone function on a bracket [lo, hi] where it changes sign: Newton's method,
/// falling back to bisection whenever a Newton step would leave the bracket, which shrinks at every iteration. Converges
/// quadratically near the root and never diverges; at most 200 iterations.
/// </summary>
internal static class SafeguardedNewton
{
    private const int MaxIterations = 200;

    /// <summary>The root of f on [lo, hi]; <paramref name="f"/> returns (f(s), f'(s)).</summary>
    /// <exception cref="ArgumentException">f does not change sign on the bracket.</exception>
    public static double Root(Func<double, (double Value, double Slope)> f, double lo, double hi)
    {
        var (flo, _) = f(lo);
        var (fhi, _) = f(hi);
        if (flo == 0.0)
        {
            return lo;
        }

        if (fhi == 0.0)
        {
            return hi;
        }

        if (Math.Sign(flo) == Math.Sign(fhi))
        {
            throw new ArgumentException($"f does not change sign on [{lo}, {hi}]: f = {flo} and {fhi}.");
        }

        var s = 0.5 * (lo + hi);
        for (var iteration = 0; iteration < MaxIterations; iteration++)
        {
            var (value, slope) = f(s);
            if (value == 0.0)
            {
                return s;
            }

            if (Math.Sign(value) == Math.Sign(flo))
            {
                lo = s;
            }
            else
            {
                hi = s;
            }

            var newton = s - (value / slope);
            var next = newton > Math.Min(lo, hi) && newton < Math.Max(lo, hi) ? newton : 0.5 * (lo + hi);
            if (Math.Abs(next - s) <= 4 * double.Epsilon + (1e-16 * Math.Abs(s)))
            {
                return next;
            }

            s = next;
        }

        return s;
    }
}
