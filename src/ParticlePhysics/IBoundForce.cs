namespace ParticlePhysics;

/// <summary>
/// A force generator that names particles by index and was built for one particle system: the system checks,
/// when the generator is added, that it is the one the indices were validated against.
/// </summary>
internal interface IBoundForce
{
    /// <summary>The particle system whose particles this generator names, or null when it names none.</summary>
    ParticleWorld? System { get; }
}
