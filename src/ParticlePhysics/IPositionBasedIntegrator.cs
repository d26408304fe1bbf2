namespace ParticlePhysics;

/// <summary>
/// An integrator that enforces the constraint sets itself, inside its substeps (<see cref="IConstraintSet.Project"/>
/// and <see cref="IConstraintSet.SolveVelocities"/> through <see cref="IPositionBasedSystem"/>): after such a step the
/// world does not run the <see cref="IConstraintSet.Resolve"/> stage, which would correct the constraints a second
/// time.
/// </summary>
public interface IPositionBasedIntegrator : IIntegrator
{
    /// <summary>The number of substeps each step is split into (each one projection pass).</summary>
    int Substeps { get; }
}
