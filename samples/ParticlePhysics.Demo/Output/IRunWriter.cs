using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Demo.Output;

/// <summary>Writes one run in one format: a header, the rows as they come, then how the run ended.</summary>
internal interface IRunWriter
{
    /// <summary>Starts the output.</summary>
    void Begin(ScenarioSetup setup, RunPlan plan);

    /// <summary>Writes one row, laid out as <see cref="ScenarioSetup.Columns"/>.</summary>
    void WriteRow(double[] row);

    /// <summary>Ends the output (the rows written so far stay, also after a divergence) and flushes it.</summary>
    void End(RunOutcome outcome);
}
