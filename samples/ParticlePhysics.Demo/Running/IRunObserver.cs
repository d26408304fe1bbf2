namespace ParticlePhysics.Demo.Running;

/// <summary>
/// Something that watches a run besides the output writer (a chart, an animation): it picks the steps it needs,
/// which the runner hands over even off the output stride, and sees how the run ended.
/// </summary>
internal interface IRunObserver
{
    /// <summary>True for the steps whose rows the observer needs. Called once per step, in increasing order.</summary>
    bool Wants(int step);

    /// <summary>Sees the row of a wanted step (the array is reused by the runner: copy what you keep).</summary>
    void Add(int step, double[] row);

    /// <summary>Sees how the run ended; <see cref="RunOutcome.FinalRow"/> is the last good state.</summary>
    void Finish(RunOutcome outcome);
}
