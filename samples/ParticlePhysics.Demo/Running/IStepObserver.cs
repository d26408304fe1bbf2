namespace ParticlePhysics.Demo.Running;

/// <summary>Watches every committed step of one run (one instance per run), for columns that need the whole history.</summary>
internal interface IStepObserver
{
    /// <summary>Called after each committed step.</summary>
    void AfterStep(ParticleWorld world);
}
