using System;
using System.Globalization;

namespace ParticlePhysics;

/// <summary>
/// Thrown by an integrator whose solver cannot reach its tolerance within its bound: implicit Euler's conjugate
/// gradients within <c>MaxIterations</c> (when asked to fail rather than continue), the adaptive RK45 within its most
/// internal steps or above its smallest step. The step is not committed: the system and the integrator stay as they were.
/// </summary>
public sealed class SolverNotConvergedException : Exception
{
    /// <summary>Creates the exception.</summary>
    /// <param name="time">The time the step was to reach.</param>
    /// <param name="iterations">The iterations spent.</param>
    /// <param name="residual">The relative residual reached.</param>
    /// <param name="tolerance">The tolerance asked for.</param>
    public SolverNotConvergedException(double time, int iterations, double residual, double tolerance)
        : base(string.Format(
            CultureInfo.InvariantCulture,
            "The implicit solve for the step to t={0:R} did not converge: relative residual {1:R} after {2} iterations, "
            + "tolerance {3:R}. Raise MaxIterations, loosen Tolerance, or take a smaller step.",
            time,
            residual,
            iterations,
            tolerance))
    {
        Time = time;
        Iterations = iterations;
        Residual = residual;
        Tolerance = tolerance;
    }

    /// <summary>Creates the exception with a message of the solver's own (the adaptive integrators' work bounds).</summary>
    /// <param name="time">The time the step was to reach.</param>
    /// <param name="iterations">The iterations (internal steps) spent.</param>
    /// <param name="residual">The last error measure reached, relative to the tolerance's scale.</param>
    /// <param name="tolerance">The tolerance asked for.</param>
    /// <param name="message">The whole message: what bound was reached and what to change.</param>
    public SolverNotConvergedException(double time, int iterations, double residual, double tolerance, string message)
        : base(message)
    {
        Time = time;
        Iterations = iterations;
        Residual = residual;
        Tolerance = tolerance;
    }

    /// <summary>The time the step was to reach, in seconds.</summary>
    public double Time { get; }

    /// <summary>The iterations spent.</summary>
    public int Iterations { get; }

    /// <summary>The relative residual reached.</summary>
    public double Residual { get; }

    /// <summary>The tolerance asked for.</summary>
    public double Tolerance { get; }
}
