using System;

namespace ParticlePhysics.Numerics;

/// <summary>
/// Sine, cosine and atan2 from + - * / and sqrt alone, so that a step that needs them (a gust of wind) gives the same bits on every
/// runtime: Math.Sin calls the platform's libm, whose last bit differs between glibc, the CRT, Mono and IL2CPP
/// builds. Box2D and Jitter2 write their own for the same reason.
/// </summary>
/// <remarks>
/// x = k pi/2 + r with k the nearest whole number to x 2/pi and |r| &lt;= pi/4, reduced in three parts (Cody and Waite):
/// pi/2 = P1 + P2 + P3 with P1 and P2 of 33 significant bits, so that k P1 and k P2 are exact for |k| &lt; 2^20 (|x| up
/// to about 1.6e6) and r carries no error beyond the last part's. Then sin r and cos r by the minimax polynomials of
/// fdlibm's kernels (degree 13 and 14 on [-pi/4, pi/4], error below 2^-58), and the quadrant k mod 4 picks
/// sin or cos and the sign. Within 1e-15 of the exact values for |x| up to 1.6e6 (tested against Math.Sin); beyond,
/// still the same bits everywhere, with the reduction's error growing as |x|.
/// </remarks>
internal static class DeterministicTrig
{
    private const double TwoOverPi = 6.36619772367581382433e-01;
    private const double HalfPi1 = 1.57079632673412561417e+00;   // the first 33 bits of pi/2
    private const double HalfPi2 = 6.07710050630396597660e-11;   // the next 33 bits
    private const double HalfPi3 = 2.02226624879595063154e-21;   // the rest

    // fdlibm's __kernel_sin and __kernel_cos coefficients.
    private const double S1 = -1.66666666666666324348e-01;
    private const double S2 = 8.33333333332248946124e-03;
    private const double S3 = -1.98412698298579493134e-04;
    private const double S4 = 2.75573137070700676789e-06;
    private const double S5 = -2.50507602534068634195e-08;
    private const double S6 = 1.58969099521155010221e-10;
    private const double C1 = 4.16666666666666019037e-02;
    private const double C2 = -1.38888888888741095749e-03;
    private const double C3 = 2.48015872894767294178e-05;
    private const double C4 = -2.75573143513906633035e-07;
    private const double C5 = 2.08757232129817482790e-09;
    private const double C6 = -1.13596475577881948265e-11;

    // Past this, k no longer fits a long's exact range of doubles; the result is NaN, as for infinities.
    private const double Largest = 1e15;

    /// <summary>sin x (NaN for a non-finite x or |x| beyond 1e15).</summary>
    public static double Sin(double x)
    {
        var quadrant = Reduce(x, out var r);
        return Select(quadrant, SinKernel(r), CosKernel(r));
    }

    /// <summary>cos x (NaN for a non-finite x or |x| beyond 1e15).</summary>
    public static double Cos(double x)
    {
        var quadrant = Reduce(x, out var r);
        return Select(quadrant + 1, SinKernel(r), CosKernel(r));
    }

    /// <summary>
    /// The angle of (x, y) in (-pi, pi], as <see cref="Math.Atan2"/> gives it (signed zeros included), NaN when either is
    /// not finite. Within 1e-15 of Math.Atan2 (tested).
    /// </summary>
    /// <remarks>
    /// The octant brings the ratio t = min / max of |x| and |y| into [0, 1]; two halvings atan t = 2 atan(t / (1 +
    /// sqrt(1 + t^2))) bring it below tan(pi/16) = 0.199, where the alternating series u - u^3/3 + ... to u^25 leaves
    /// under 1e-19; then the octant's reflections pi/2 - a and pi - a, and the sign of y.
    /// </remarks>
    public static double Atan2(double y, double x)
    {
        if (!(Math.Abs(x) <= double.MaxValue && Math.Abs(y) <= double.MaxValue))
        {
            return double.NaN;
        }

        double ax = Math.Abs(x), ay = Math.Abs(y);
        var steep = ay > ax;
        var a = ax == 0.0 && ay == 0.0 ? 0.0 : AtanOfFraction(steep ? ax / ay : ay / ax);
        if (steep)
        {
            a = (0.5 * Math.PI) - a;
        }

        if (x < 0.0 || (x == 0.0 && BitConverter.DoubleToInt64Bits(x) < 0))
        {
            a = Math.PI - a;
        }

        return y < 0.0 || (y == 0.0 && BitConverter.DoubleToInt64Bits(y) < 0) ? -a : a;
    }

    // atan t for 0 <= t <= 1.
    private static double AtanOfFraction(double t)
    {
        var u = t / (1.0 + Math.Sqrt(1.0 + (t * t)));
        u /= 1.0 + Math.Sqrt(1.0 + (u * u));
        var z = u * u;
        var series = 0.0;
        for (var k = 25; k >= 3; k -= 2)
        {
            series = ((k & 2) == 0 ? 1.0 / k : -1.0 / k) + (z * series);
        }

        return 4.0 * (u + (u * z * series));
    }

    /// <summary>
    /// sin(r + q pi/2) from sin r and cos r: quadrant 0 sin, 1 cos, 2 -sin, 3 -cos, chosen by bits rather than by
    /// branches (the quadrant of a gust's phase changes from one triangle to the next, and a mispredicted branch costs
    /// more than both kernels). A negative quadrant (x not reducible) gives NaN.
    /// </summary>
    private static double Select(int quadrant, double sin, double cos)
    {
        var odd = -(long)(quadrant & 1); // all ones for cos
        var bits = (BitConverter.DoubleToInt64Bits(sin) & ~odd) | (BitConverter.DoubleToInt64Bits(cos) & odd);
        bits ^= (long)(quadrant & 2) << 62; // the sign bit for quadrants 2 and 3
        return quadrant < 0 ? double.NaN : BitConverter.Int64BitsToDouble(bits);
    }

    /// <summary>k mod 4 (0 to 3) and r = x - k pi/2, or -1 where x cannot be reduced.</summary>
    private static int Reduce(double x, out double r)
    {
        if (!(x >= -Largest && x <= Largest))
        {
            r = double.NaN;
            return -1;
        }

        // The nearest whole number, halves away from zero (symmetric, so sin(-x) = -sin(x) to the bit).
        var scaled = x * TwoOverPi;
        var k = (long)(scaled >= 0.0 ? scaled + 0.5 : scaled - 0.5);
        double kd = k;
        r = ((x - (kd * HalfPi1)) - (kd * HalfPi2)) - (kd * HalfPi3);
        return (int)(k & 3);
    }

    private static double SinKernel(double r)
    {
        var z = r * r;
        return r + (r * z * (S1 + (z * (S2 + (z * (S3 + (z * (S4 + (z * (S5 + (z * S6)))))))))));
    }

    private static double CosKernel(double r)
    {
        var z = r * r;
        var tail = z * z * (C1 + (z * (C2 + (z * (C3 + (z * (C4 + (z * (C5 + (z * C6))))))))));

        // 1 - z/2 computed as fdlibm does near pi/4 would gain a last bit there; the plain sum is within 1e-16.
        return 1.0 - (0.5 * z) + tail;
    }
}
