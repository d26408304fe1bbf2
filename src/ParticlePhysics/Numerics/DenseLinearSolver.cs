using System;

namespace ParticlePhysics.Numerics;

/// <summary>
/// Direct solves of small dense systems A x = b, A n x n row-major and factored in place, allocating nothing: LU with
/// partial pivoting for any non-singular A, Cholesky for a symmetric positive definite one (half the work, no
/// pivoting). The band counterpart of the second is <see cref="BandedCholesky"/>.
/// </summary>
/// <remarks>
/// LU (Gaussian elimination): for each column the row with the largest magnitude is swapped up, then
/// a_rk -= (a_rc / a_cc) a_ck below it (b alike), which leaves U above the diagonal; x by back substitution,
/// x_r = (b_r - sum_{k &gt; r} u_rk x_k) / u_rr. Cholesky: A = L L^T with
/// l_jj = sqrt(a_jj - sum_{k &lt; j} l_jk^2) and l_ij = (a_ij - sum_{k &lt; j} l_ik l_jk) / l_jj for i &gt; j, then
/// L y = b forward and L^T x = y backward. Written here rather than taken from a library because the core has no
/// dependencies and must give the same bits on .NET and Mono: every sum runs in increasing k.
/// </remarks>
internal static class DenseLinearSolver
{
    /// <summary>
    /// Solves A x = b in place by LU with partial pivoting (<paramref name="a"/> becomes its factors, <paramref name="b"/>
    /// becomes x; <paramref name="pivots"/>[c] the row swapped into row c). False as soon as a pivot's magnitude is at most
    /// <paramref name="smallestPivot"/> (0: exactly singular), with a and b then part-way through the elimination.
    /// </summary>
    public static bool SolveLu(Span<double> a, Span<int> pivots, Span<double> b, int n, double smallestPivot = 0.0)
    {
        Check(a, b, n);
        if (pivots.Length < n)
        {
            throw new ArgumentException($"The LU of an {n} x {n} matrix needs {n} pivots; got {pivots.Length}.", nameof(pivots));
        }

        for (var col = 0; col < n; col++)
        {
            var pivot = col;
            for (var row = col + 1; row < n; row++)
            {
                if (Math.Abs(a[(row * n) + col]) > Math.Abs(a[(pivot * n) + col]))
                {
                    pivot = row;
                }
            }

            if (Math.Abs(a[(pivot * n) + col]) <= smallestPivot)
            {
                return false;
            }

            pivots[col] = pivot;
            if (pivot != col)
            {
                for (var k = 0; k < n; k++)
                {
                    (a[(col * n) + k], a[(pivot * n) + k]) = (a[(pivot * n) + k], a[(col * n) + k]);
                }

                (b[col], b[pivot]) = (b[pivot], b[col]);
            }

            for (var row = col + 1; row < n; row++)
            {
                var factor = a[(row * n) + col] / a[(col * n) + col];
                for (var k = col; k < n; k++)
                {
                    a[(row * n) + k] -= factor * a[(col * n) + k];
                }

                b[row] -= factor * b[col];
            }
        }

        for (var row = n - 1; row >= 0; row--)
        {
            var sum = b[row];
            for (var k = row + 1; k < n; k++)
            {
                sum -= a[(row * n) + k] * b[k];
            }

            b[row] = sum / a[(row * n) + row];
        }

        return true;
    }

    /// <summary>
    /// Factors A = L L^T in place: L in the lower triangle of <paramref name="a"/> (the upper triangle is not read or
    /// written). False when a pivot a_jj - sum l_jk^2 is not positive and finite: A is not (numerically) positive
    /// definite, and the factor is left part-way.
    /// </summary>
    public static bool FactorCholesky(Span<double> a, int n)
    {
        Check(a, a, n);
        for (var j = 0; j < n; j++)
        {
            var s = a[(j * n) + j];
            for (var k = 0; k < j; k++)
            {
                s -= a[(j * n) + k] * a[(j * n) + k];
            }

            if (!(s > 0.0) || double.IsInfinity(s))
            {
                return false;
            }

            var pivot = Math.Sqrt(s);
            a[(j * n) + j] = pivot;
            for (var i = j + 1; i < n; i++)
            {
                var t = a[(i * n) + j];
                for (var k = 0; k < j; k++)
                {
                    t -= a[(i * n) + k] * a[(j * n) + k];
                }

                a[(i * n) + j] = t / pivot;
            }
        }

        return true;
    }

    /// <summary>
    /// x = A^-1 b from the factor of <see cref="FactorCholesky"/>: L y = b into <paramref name="x"/>, then L^T x = y in
    /// place. <paramref name="b"/> and <paramref name="x"/> may be the same memory.
    /// </summary>
    public static void SolveCholesky(ReadOnlySpan<double> factor, int n, ReadOnlySpan<double> b, Span<double> x)
    {
        var l = factor.ForReading();
        var rhs = b.ForReading();
        Check(l, x, n);
        if (rhs.Length < n)
        {
            throw new ArgumentException($"The right-hand side needs {n} values; got {rhs.Length}.", nameof(b));
        }

        for (var i = 0; i < n; i++)
        {
            var s = rhs[i];
            for (var k = 0; k < i; k++)
            {
                s -= l[(i * n) + k] * x[k];
            }

            x[i] = s / l[(i * n) + i];
        }

        for (var i = n - 1; i >= 0; i--)
        {
            var s = x[i];
            for (var k = i + 1; k < n; k++)
            {
                s -= l[(k * n) + i] * x[k];
            }

            x[i] = s / l[(i * n) + i];
        }
    }

    private static void Check(Span<double> a, Span<double> vector, int n)
    {
        if (n < 0 || a.Length < (long)n * n || vector.Length < n)
        {
            throw new ArgumentException(
                $"A dense solve of order {n} needs {(long)n * n} matrix values and {n} vector values; got {a.Length} and {vector.Length}.");
        }
    }
}
