namespace ParticlePhysics;

/// <summary>
/// A constraint set that stands in for a force generator under a position-based integrator: there, the world leaves
/// <see cref="Force"/> out of the accelerations and the set projects it instead (springs as distance constraints of
/// compliance 1 / k). Under the force-based integrators the generator acts as a force and the set does nothing.
/// </summary>
public interface IForceProjection : IConstraintSet
{
    /// <summary>The generator this set projects.</summary>
    IForceGenerator Force { get; }
}
