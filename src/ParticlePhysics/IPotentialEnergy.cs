namespace ParticlePhysics;

/// <summary>
/// A conservative force that can report its potential energy, so that the total mechanical energy of a system
/// (kinetic + potential) can be monitored. Implemented by gravity and by the springs.
/// </summary>
public interface IPotentialEnergy
{
    /// <summary>The potential energy, in joules, of the configuration in <paramref name="state"/>.</summary>
    /// <param name="state">The positions (and masses) to evaluate at.</param>
    double PotentialEnergy(in ParticleState state);
}
