using System;

namespace ParticlePhysics.Numerics;

/// <summary>
/// Cholesky factorisation A = L L^T of a symmetric positive definite band matrix, in place, and the solve of A x = b:
/// the direct solver of the constraint matrix J W J^T of a chain of rods (band 1: tridiagonal) or any set whose
/// constraints only couple to neighbours a few indices away. O(n b^2) to factor, O(n b) to solve, no allocation.
/// </summary>
/// <remarks>
/// Storage: row i holds A[i, i - b] .. A[i, i] in <c>band[i (b + 1) .. i (b + 1) + b]</c>, the diagonal last (entries
/// before column 0 are ignored). L overwrites it. Derivation: L_ij = (A_ij - sum_k L_ik L_jk) / L_jj for j &lt; i and
/// L_ii = sqrt(A_ii - sum_k L_ik^2), the sums over the k &lt; j within the band of both rows. A pivot that is not
/// positive beyond rounding (a redundant constraint: J W J^T is then only semi-definite) is replaced by a relative 1e-12
/// of its diagonal, which gives the redundant multipliers a negligible share instead of a division by zero.
/// </remarks>
internal static class BandedCholesky
{
    private const double PivotFloor = 1e-12;

    /// <summary>Factors the band matrix of <paramref name="n"/> rows and half-bandwidth <paramref name="bandwidth"/> in place.</summary>
    public static void Factor(Span<double> band, int n, int bandwidth)
    {
        var stride = bandwidth + 1;
        for (var i = 0; i < n; i++)
        {
            var row = i * stride;
            var firstColumn = Math.Max(0, i - bandwidth);
            for (var j = firstColumn; j <= i; j++)
            {
                var other = j * stride;

                // Entry (i, k) sits at row + bandwidth - (i - k); entry (j, k) at other + bandwidth - (j - k).
                var sum = band[row + bandwidth - (i - j)];
                var kStart = Math.Max(firstColumn, j - bandwidth);
                for (var k = kStart; k < j; k++)
                {
                    sum -= band[row + bandwidth - (i - k)] * band[other + bandwidth - (j - k)];
                }

                if (j < i)
                {
                    band[row + bandwidth - (i - j)] = sum / band[other + bandwidth];
                }
                else
                {
                    var diagonal = band[row + bandwidth];
                    var floor = PivotFloor * Math.Abs(diagonal);
                    band[row + bandwidth] = Math.Sqrt(sum > floor ? sum : Math.Max(floor, double.Epsilon));
                }
            }
        }
    }

    /// <summary>Solves L L^T x = b with the factor from <see cref="Factor"/>; <paramref name="x"/> holds b on entry.</summary>
    public static void Solve(ReadOnlySpan<double> band, int n, int bandwidth, Span<double> x)
    {
        var factor = band.ForReading();
        var stride = bandwidth + 1;
        for (var i = 0; i < n; i++)
        {
            var row = i * stride;
            var sum = x[i];
            for (var k = Math.Max(0, i - bandwidth); k < i; k++)
            {
                sum -= factor[row + bandwidth - (i - k)] * x[k];
            }

            x[i] = sum / factor[row + bandwidth];
        }

        for (var i = n - 1; i >= 0; i--)
        {
            var sum = x[i];
            var last = Math.Min(n - 1, i + bandwidth);
            for (var k = i + 1; k <= last; k++)
            {
                sum -= factor[(k * stride) + bandwidth - (k - i)] * x[k];
            }

            x[i] = sum / factor[(i * stride) + bandwidth];
        }
    }
}
