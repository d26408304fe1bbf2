namespace ParticlePhysics.Demo.Running;

/// <summary>
/// How a run ended: its last good row and step, the error there, the divergence that stopped it (if any), and
/// whether the user interrupted it (Ctrl-C).
/// </summary>
internal sealed record RunOutcome(double[] FinalRow, int FinalStep, double FinalTime, double? FinalError, Divergence? Diverged, bool Interrupted = false);

/// <summary>
/// A step that failed: the time it was to reach (step * dt) and the core's description, a
/// <see cref="SimulationDivergedException"/> or (rk45 at a bound of its work) a <see cref="SolverNotConvergedException"/>.
/// </summary>
internal sealed record Divergence(int Step, double Time, System.Exception Exception);
