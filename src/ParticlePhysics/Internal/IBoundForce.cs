namespace ParticlePhysics.Internal;

/// <summary>
/// A force generator that names particles by index and was built for one particle system: the system checks,
/// when the generator is added, that it is the one the indices were validated against.
/// </summary>
internal interface IBoundForce
{
    /// <summary>
    /// The <see cref="ParticleWorld"/> whose particles this generator names, or null when it names none (an object,
    /// compared by reference, so that this namespace uses nothing of the core).
    /// </summary>
    object? World { get; }
}
