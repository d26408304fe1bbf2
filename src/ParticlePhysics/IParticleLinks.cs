namespace ParticlePhysics;

/// <summary>
/// What a force generator or constraint set tells the world's sleeping (<see cref="ParticleWorld.SleepSpeed"/>): which
/// particles it ties together, so that they sleep and wake as one island, and when it has changed in a way that may
/// move a particle at rest.
/// </summary>
/// <remarks>
/// A world sleeps only while every one of its force generators and constraint sets implements this: one that does not
/// may push a resting particle through a coupling the islands do not know, so the world keeps every particle awake.
/// A generator that acts on each particle alone (a uniform field) implements it with no links.
/// </remarks>
public interface IParticleLinks
{
    /// <summary>
    /// A number that changes whenever the generator or set is changed in a way that may move a particle at rest (a new
    /// gravity, an obstacle added or removed): the world wakes every particle at the next step when it does.
    /// </summary>
    int Revision { get; }

    /// <summary>Links the particles this generator or set ties together at the end of the step just committed.</summary>
    void AddLinks(ParticleIslands islands);
}
