using System;

namespace ParticlePhysics.Numerics;

/// <summary>
/// exp(A t) for the small dense matrices of the linear scenarios (the two-mass chain's 5 x 5 affine system).
/// Scaling and squaring: exp(M) = exp(M / 2^s)^(2^s), with s chosen so that |M / 2^s|_1 &lt;= 1/2, and the Taylor
/// series of the scaled matrix summed until its terms stop changing the result (at most 30 terms; at norm 1/2
/// the truncation error is below 1e-30). Written here because the core has no package dependencies.
/// </summary>
internal static class MatrixExponential
{
    public static double[,] Exp(double[,] a, double t)
    {
        var n = a.GetLength(0);
        var m = new double[n, n];
        for (var i = 0; i < n; i++)
        {
            for (var j = 0; j < n; j++)
            {
                m[i, j] = a[i, j] * t;
            }
        }

        var norm = OneNorm(m);
        var squarings = norm > 0.5 ? (int)Math.Ceiling(Math.Log(norm / 0.5, 2)) : 0;
        var scale = Math.Pow(2, -squarings);
        for (var i = 0; i < n; i++)
        {
            for (var j = 0; j < n; j++)
            {
                m[i, j] *= scale;
            }
        }

        var result = Identity(n);
        var term = Identity(n);
        for (var k = 1; k <= 30; k++)
        {
            term = Multiply(term, m);
            var changed = false;
            for (var i = 0; i < n; i++)
            {
                for (var j = 0; j < n; j++)
                {
                    term[i, j] /= k;
                    var before = result[i, j];
                    result[i, j] += term[i, j];
                    changed |= result[i, j] != before;
                }
            }

            if (!changed)
            {
                break;
            }
        }

        for (var s = 0; s < squarings; s++)
        {
            result = Multiply(result, result);
        }

        return result;
    }

    public static void Apply(double[,] matrix, ReadOnlySpan<double> vector, Span<double> result)
    {
        var x = vector.ForReading();
        var n = vector.Length;
        for (var i = 0; i < n; i++)
        {
            var sum = 0.0;
            for (var j = 0; j < n; j++)
            {
                sum += matrix[i, j] * x[j];
            }

            result[i] = sum;
        }
    }

    private static double[,] Identity(int n)
    {
        var identity = new double[n, n];
        for (var i = 0; i < n; i++)
        {
            identity[i, i] = 1.0;
        }

        return identity;
    }

    private static double[,] Multiply(double[,] a, double[,] b)
    {
        var n = a.GetLength(0);
        var c = new double[n, n];
        for (var i = 0; i < n; i++)
        {
            for (var k = 0; k < n; k++)
            {
                var aik = a[i, k];
                for (var j = 0; j < n; j++)
                {
                    c[i, j] += aik * b[k, j];
                }
            }
        }

        return c;
    }

    private static double OneNorm(double[,] m)
    {
        var n = m.GetLength(0);
        var largest = 0.0;
        for (var j = 0; j < n; j++)
        {
            var sum = 0.0;
            for (var i = 0; i < n; i++)
            {
                sum += Math.Abs(m[i, j]);
            }

            largest = Math.Max(largest, sum);
        }

        return largest;
    }
}
