namespace ParticlePhysics.Demo.Running;

/// <summary>How a run ended: its last good row and step, the error there, and the divergence that stopped it, if any.</summary>
internal sealed record RunOutcome(double[] FinalRow, int FinalStep, double FinalTime, double? FinalError, Divergence? Diverged);

/// <summary>A step that diverged: the time it was to reach (step * dt) and the core's description.</summary>
internal sealed record Divergence(int Step, double Time, SimulationDivergedException Exception);
