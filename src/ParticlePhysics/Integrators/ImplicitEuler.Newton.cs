using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Integrators;

// Backward Euler for any other IOdeSystem: y1 = y0 + h f(t + h, y1) by Newton's method with a finite-difference
// Jacobian and a dense LU factorisation (small systems such as the course's scalar ODE).
public sealed partial class ImplicitEuler
{
    /// <summary>Newton's method on a plain ODE stops when its update is this small relative to 1 + |y|.</summary>
    private const double NewtonTolerance = 1e-12;

    // Plain-ODE path.
    private double[]? _newtonY;
    private double[]? _newtonF;
    private double[]? _newtonFShifted;
    private double[]? _newtonMatrix;
    private double[]? _newtonDelta;
    private int[]? _pivots;

    /// <summary>Newton on G(y) = y - y0 - h f(t + h, y) = 0, with a forward-difference Jacobian and partial-pivot LU.</summary>
    private void StepNewton(IOdeSystem system, double time, ReadOnlySpan<double> state, Span<double> next, double h)
    {
        var n = state.Length;
        var y0 = state.ForReading();
        var y = _newtonY = StepChecks.Sized(_newtonY, n);
        var f = _newtonF = StepChecks.Sized(_newtonF, n);
        var shifted = _newtonFShifted = StepChecks.Sized(_newtonFShifted, n);
        var matrix = _newtonMatrix = StepChecks.Sized(_newtonMatrix, n * n);
        var delta = _newtonDelta = StepChecks.Sized(_newtonDelta, n);
        var pivots = _pivots = _pivots is not null && _pivots.Length == n ? _pivots : new int[n];
        var end = time + h;

        state.CopyTo(y);
        var iterations = 0;
        var update = double.PositiveInfinity;
        while (iterations < _maxIterations)
        {
            system.Evaluate(end, y, f);
            for (var j = 0; j < n; j++)
            {
                // Column j of dG/dy = I - h df/dy by a forward difference in y_j.
                var original = y[j];
                var epsilon = 1.4901161193847656e-8 * Math.Max(1.0, Math.Abs(original));
                y[j] = original + epsilon;
                system.Evaluate(end, y, shifted);
                y[j] = original;
                for (var i = 0; i < n; i++)
                {
                    matrix[(i * n) + j] = (i == j ? 1.0 : 0.0) - (h * (shifted[i] - f[i]) / epsilon);
                }
            }

            for (var i = 0; i < n; i++)
            {
                delta[i] = -(y[i] - y0[i] - (h * f[i]));
            }

            if (!DenseLinearSolver.SolveLu(matrix, pivots, delta, n))
            {
                break;
            }

            update = 0.0;
            for (var i = 0; i < n; i++)
            {
                y[i] += delta[i];
                update = Math.Max(update, Math.Abs(delta[i]) / (1.0 + Math.Abs(y[i])));
            }

            iterations++;
            if (update <= NewtonTolerance || !DoubleChecks.IsFinite(update))
            {
                break;
            }
        }

        LastIterations = iterations;
        LastResidual = update;
        LastConverged = update <= NewtonTolerance;
        y.AsSpan().CopyTo(next);
    }
}
