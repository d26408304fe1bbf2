using System;
using System.Linq;
using ParticlePhysics.Numerics;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Numerics;

/// <summary>
/// The dense direct solver of implicit Euler's Newton and warm start (LU) and of the multigrid's coarsest level
/// (Cholesky), against systems built from an exact answer: small integers, for which every step of the elimination
/// is exact, so the answer must come back to the last bit.
/// </summary>
public class DenseLinearSolverTests
{
    [Fact]
    public void Cholesky_gives_back_the_integer_factor_and_the_integer_solution_exactly()
    {
        // A = L L^T for an integer L with positive diagonal: each l_jj is the square root of a perfect square and each
        // numerator a_ij - sum l_ik l_jk is exactly l_ij l_jj, so the factor is L itself; for b = A x with integer x
        // both substitutions divide exact multiples of the diagonal too.
        var random = new SeededRandom(2026);
        const int n = 7;
        var l = new double[n * n];
        for (var i = 0; i < n; i++)
        {
            for (var j = 0; j < i; j++)
            {
                l[(i * n) + j] = Math.Floor(random.NextDouble() * 9.0) - 4.0;
            }

            l[(i * n) + i] = 1.0 + Math.Floor(random.NextDouble() * 3.0);
        }

        var a = LowerTimesTranspose(l, n);
        var x = Enumerable.Range(0, n).Select(i => (double)((i % 3) - 1 + (2 * i))).ToArray();
        var b = Multiply(a, x, n);

        var factor = (double[])a.Clone();
        Assert.True(DenseLinearSolver.FactorCholesky(factor, n));
        for (var i = 0; i < n; i++)
        {
            for (var j = 0; j <= i; j++)
            {
                Assert.Equal(l[(i * n) + j], factor[(i * n) + j]);
            }
        }

        var solution = new double[n];
        DenseLinearSolver.SolveCholesky(factor, n, b, solution);
        Assert.Equal(x, solution);

        // The right-hand side and the solution may share their memory.
        var inPlace = (double[])b.Clone();
        DenseLinearSolver.SolveCholesky(factor, n, inPlace, inPlace);
        Assert.Equal(x, inPlace);
    }

    [Fact]
    public void Cholesky_refuses_a_matrix_that_is_not_positive_definite_or_not_finite()
    {
        Assert.False(DenseLinearSolver.FactorCholesky(new[] { 1.0, 2.0, 2.0, 1.0 }, 2)); // eigenvalues 3 and -1
        Assert.False(DenseLinearSolver.FactorCholesky(new[] { 1.0, 1.0, 1.0, 1.0 }, 2)); // singular: the second pivot is 0
        Assert.False(DenseLinearSolver.FactorCholesky(new[] { double.PositiveInfinity }, 1));
        Assert.False(DenseLinearSolver.FactorCholesky(new[] { double.NaN }, 1));
        Assert.True(DenseLinearSolver.FactorCholesky(new[] { 4.0, 2.0, 2.0, 5.0 }, 2)); // L = [2 0; 1 2]
    }

    [Fact]
    public void Lu_solves_a_system_that_needs_pivoting_exactly()
    {
        // A zero in the first pivot's place: elimination without row swaps would divide by it. With partial pivoting
        // on this integer matrix every multiplier and every update is a whole number or an exact half.
        var a = new double[]
        {
            0, 2, 1,
            4, 1, 0,
            2, 1, 3,
        };
        var x = new[] { 1.0, -2.0, 3.0 };
        var b = Multiply(a, x, 3);
        var pivots = new int[3];
        Assert.True(DenseLinearSolver.SolveLu(a, pivots, b, 3));
        Assert.Equal(x, b);
        Assert.Equal(1, pivots[0]); // the 4 of row 1 is the largest in column 0
    }

    [Fact]
    public void Lu_matches_the_answer_of_a_random_well_conditioned_system_to_rounding()
    {
        // Diagonally dominant: the condition number is small, so the solve agrees with the chosen x to a few ulps.
        var random = new SeededRandom(20260601);
        const int n = 12;
        var a = new double[n * n];
        for (var i = 0; i < n; i++)
        {
            for (var j = 0; j < n; j++)
            {
                a[(i * n) + j] = random.NextDouble() - 0.5;
            }

            a[(i * n) + i] += n;
        }

        var x = Enumerable.Range(0, n).Select(_ => random.NextDouble() - 0.5).ToArray();
        var b = Multiply(a, x, n);
        Assert.True(DenseLinearSolver.SolveLu(a, new int[n], b, n));
        for (var i = 0; i < n; i++)
        {
            Assert.True(Math.Abs(b[i] - x[i]) <= 1e-14, $"x[{i}] = {b[i]:R}, expected {x[i]:R}");
        }
    }

    [Fact]
    public void Lu_refuses_a_singular_matrix_and_a_pivot_below_the_floor_it_is_given()
    {
        var singular = new double[] { 1, 2, 2, 4 }; // the second row twice the first
        Assert.False(DenseLinearSolver.SolveLu(singular, new int[2], new double[] { 1, 2 }, 2));

        // Pivots 1 and 1e-10: accepted with no floor, refused with a floor of 1e-8.
        Assert.True(DenseLinearSolver.SolveLu(new double[] { 1, 0, 0, 1e-10 }, new int[2], new double[] { 1, 1 }, 2));
        Assert.False(DenseLinearSolver.SolveLu(new double[] { 1, 0, 0, 1e-10 }, new int[2], new double[] { 1, 1 }, 2, 1e-8));
    }

    [Fact]
    public void Sizes_that_do_not_fit_the_order_are_refused_before_anything_is_read()
    {
        Assert.Throws<ArgumentException>(() => DenseLinearSolver.SolveLu(new double[8], new int[3], new double[3], 3));
        Assert.Throws<ArgumentException>(() => DenseLinearSolver.SolveLu(new double[9], new int[2], new double[3], 3));
        Assert.Throws<ArgumentException>(() => DenseLinearSolver.SolveLu(new double[9], new int[3], new double[2], 3));
        Assert.Throws<ArgumentException>(() => DenseLinearSolver.FactorCholesky(new double[3], 2));
        Assert.Throws<ArgumentException>(() => DenseLinearSolver.SolveCholesky(new double[4], 2, new double[1], new double[2]));
        Assert.Throws<ArgumentException>(() => DenseLinearSolver.SolveCholesky(new double[4], 2, new double[2], new double[1]));
    }

    private static double[] LowerTimesTranspose(double[] l, int n)
    {
        var a = new double[n * n];
        for (var i = 0; i < n; i++)
        {
            for (var j = 0; j < n; j++)
            {
                var sum = 0.0;
                for (var k = 0; k <= Math.Min(i, j); k++)
                {
                    sum += l[(i * n) + k] * l[(j * n) + k];
                }

                a[(i * n) + j] = sum;
            }
        }

        return a;
    }

    private static double[] Multiply(double[] a, double[] x, int n)
    {
        var y = new double[n];
        for (var i = 0; i < n; i++)
        {
            for (var k = 0; k < n; k++)
            {
                y[i] += a[(i * n) + k] * x[k];
            }
        }

        return y;
    }
}
