namespace ParticlePhysics.Demo.Running;

/// <summary>
/// How a run ended: its last good row and step, the error there, the divergence that stopped it (if any), and
/// whether the user interrupted it (Ctrl-C).
/// </summary>
internal sealed record RunOutcome(double[] FinalRow, int FinalStep, double FinalTime, double? FinalError, Divergence? Diverged, bool Interrupted = false);

/// <summary>A step that diverged: the time it was to reach (step * dt) and the core's description.</summary>
internal sealed record Divergence(int Step, double Time, SimulationDivergedException Exception);
