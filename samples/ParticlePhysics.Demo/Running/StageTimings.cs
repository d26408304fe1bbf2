namespace ParticlePhysics.Demo.Running;

/// <summary>
/// A run's per-stage timings (<c>--profile</c>): the world's <see cref="ParticleWorld.LastStepProfile"/> after each
/// step, added up over the run, with the number of steps; a replay reads the sums at its frames.
/// </summary>
internal sealed class StageTimings
{
    /// <summary>The sum of every committed step's profile so far.</summary>
    public StepProfile Total { get; private set; }

    /// <summary>The committed steps so far.</summary>
    public int Steps { get; private set; }

    /// <summary>Switches the world's profiling on, before the first step (a plain ODE has no stages to time).</summary>
    public static void Start(ISimulation simulation)
    {
        if (simulation is ParticleSimulation particles)
        {
            particles.System.Profiling = true;
        }
    }

    /// <summary>Adds the step just committed.</summary>
    public void AfterStep(ISimulation simulation)
    {
        if (simulation is ParticleSimulation particles)
        {
            Total += particles.System.LastStepProfile;
            Steps++;
        }
    }
}
