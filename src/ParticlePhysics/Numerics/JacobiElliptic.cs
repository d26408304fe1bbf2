using System;

namespace ParticlePhysics.Numerics;

/// <summary>
/// The complete elliptic integral of the first kind K(k) and Jacobi's elliptic functions sn, cn, dn of modulus k,
/// by the arithmetic-geometric mean (descending Landen transformation): the exact solution of the pendulum.
/// </summary>
/// <remarks>
/// AGM: a0 = 1, b0 = sqrt(1 - k^2), c0 = k; a(n+1) = (a + b) / 2, b(n+1) = sqrt(a b), c(n+1) = (a - b) / 2, until c is
/// below rounding (the AGM converges quadratically). Then K = pi / (2 a_N),
/// and (Abramowitz and Stegun, 16.4) phi_N = 2^N a_N u, phi(n-1) = (phi_n + asin(c_n sin(phi_n) / a_n)) / 2,
/// sn = sin phi_0, cn = cos phi_0, dn = sqrt(cn^2 + k'^2 sn^2). The argument is first reduced modulo the real
/// period 4 K, so that phi stays small and keeps its digits.
/// </remarks>
internal static class JacobiElliptic
{
    private const int MaxTerms = 32;

    /// <summary>K(k) = integral from 0 to pi/2 of 1 / sqrt(1 - k^2 sin^2 t) dt, for a modulus 0 &lt;= k &lt; 1.</summary>
    public static double CompleteK(double k)
    {
        CheckModulus(k);
        Span<double> a = stackalloc double[MaxTerms + 1];
        Span<double> c = stackalloc double[MaxTerms + 1];
        var terms = Agm(k, a, c);
        return Math.PI / (2.0 * a[terms]);
    }

    /// <summary>sn(u, k), cn(u, k) and dn(u, k), for a modulus 0 &lt;= k &lt; 1.</summary>
    public static (double Sn, double Cn, double Dn) Functions(double u, double k)
    {
        CheckModulus(k);
        Span<double> a = stackalloc double[MaxTerms + 1];
        Span<double> c = stackalloc double[MaxTerms + 1];
        var terms = Agm(k, a, c);
        var period = 4.0 * (Math.PI / (2.0 * a[terms]));
        u -= period * Math.Round(u / period);
        if (terms == 0)
        {
            return (Math.Sin(u), Math.Cos(u), 1.0);
        }

        var phi = Math.Pow(2.0, terms) * a[terms] * u;
        for (var n = terms; n >= 1; n--)
        {
            phi = 0.5 * (phi + Math.Asin(c[n] * Math.Sin(phi) / a[n]));
        }

        // dn^2 = 1 - k^2 sn^2 = cn^2 + k'^2 sn^2, without the cancellation of the first form (A and S's
        // cos(phi_0) / cos(phi_1 - phi_0) is 0 / 0 where sn = 1).
        double sn = Math.Sin(phi), cn = Math.Cos(phi), complement = (1.0 - k) * (1.0 + k);
        return (sn, cn, Math.Sqrt((cn * cn) + (complement * sn * sn)));
    }

    /// <summary>Fills the AGM sequences a and c from (1, sqrt(1 - k^2), k); returns N, the last index.</summary>
    private static int Agm(double k, Span<double> a, Span<double> c)
    {
        a[0] = 1.0;
        c[0] = k;
        var b = Math.Sqrt((1.0 - k) * (1.0 + k));
        var n = 0;
        while (Math.Abs(c[n]) > 1e-17 * a[n] && n < MaxTerms)
        {
            a[n + 1] = 0.5 * (a[n] + b);
            c[n + 1] = 0.5 * (a[n] - b);
            b = Math.Sqrt(a[n] * b);
            n++;
        }

        return n;
    }

    private static void CheckModulus(double k)
    {
        if (!(k >= 0.0 && k < 1.0))
        {
            throw new ArgumentOutOfRangeException(nameof(k), k, $"The modulus k must be at least 0 and below 1; got {k}.");
        }
    }
}
