using System;
using System.Globalization;

namespace ParticlePhysics;

/// <summary>
/// Thrown by an implicit integrator asked to fail rather than continue when its solver does not reach its tolerance
/// within its iteration cap. The step is not committed: the system stays as it was.
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
    }

    /// <summary>The time the step was to reach, in seconds.</summary>
    public double Time { get; }

    /// <summary>The iterations spent.</summary>
    public int Iterations { get; }

    /// <summary>The relative residual reached.</summary>
    public double Residual { get; }
}
