using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Integrators.Multigrid;

/// <summary>
/// The coarsest level's solve, X = A^-1 B: a dense Cholesky factorisation of its operator
/// (<see cref="DenseLinearSolver"/>), made once per setup, for a level of at most
/// <see cref="AggregationMultigrid.CoarsestNodes"/> aggregates (a 48 x 48 matrix at most); block Jacobi, X = D^-1 B,
/// when the level is larger (the hierarchy stopped coarsening) or its operator is not positive definite.
/// </summary>
internal sealed unsafe class CoarsestSolver
{
    private double[] _factor = Array.Empty<double>();
    private CoarseLevel? _factored; // the level the factor is of, null when there is none

    /// <summary>Factorises <paramref name="level"/>'s operator, or leaves it to block Jacobi.</summary>
    public void Factor(CoarseLevel level)
    {
        _factored = null;
        if (level.Count > AggregationMultigrid.CoarsestNodes)
        {
            return;
        }

        var n = 3 * level.Count;
        if (_factor.Length != n * n)
        {
            _factor = new double[n * n];
        }

        Array.Clear(_factor, 0, _factor.Length);
        level.FillDense(_factor, n);
        _factored = DenseLinearSolver.FactorCholesky(_factor, n) ? level : null;
    }

    /// <summary>X = A^-1 B by the Cholesky factors of <paramref name="level"/>, or X = D^-1 B when there are none.</summary>
    public void Solve(CoarseLevel level)
    {
        if (_factored != level)
        {
            fixed (double* b = level.B, x = level.X, inverse = level.Inverse)
            {
                Blocks3.MultiplyAll(inverse, b, x, level.Count);
            }

            return;
        }

        DenseLinearSolver.SolveCholesky(_factor, 3 * level.Count, level.B, level.X);
    }
}
