namespace ParticlePhysics;

/// <summary>
/// The world's sleeping as a constraint set sees it inside a step (<see cref="ConstraintContext.Sleeping"/>): a
/// sleeping particle has inverse mass 0 and velocity 0 until it is woken. A set that finds something meeting a
/// sleeping particle at more than <see cref="WakeSpeed"/> wakes it, with its island, before it projects the contact,
/// so that the island takes the impact with its own masses in the same substep.
/// </summary>
public interface ISleepingParticles
{
    /// <summary>The relative speed, in m/s, above which a contact with a sleeping particle wakes it (the world's sleep speed).</summary>
    double WakeSpeed { get; }

    /// <summary>Whether the particle sleeps.</summary>
    bool IsAsleep(int particle);

    /// <summary>
    /// Whether the particle moved faster than the wake speed in the last step (its move over the step; false for one
    /// asleep): a sleeping particle it touches wakes, as a box does when the one it rests on is knocked away.
    /// </summary>
    bool MovedLastStep(int particle);

    /// <summary>
    /// Whether the particle was woken, added or set by the host since the last step: its velocity has not yet shown in a
    /// move, so a contact it approaches faster than the wake speed wakes the other side. (An older particle's velocity
    /// is not trusted alone: one held by its contacts can carry a velocity its position never realises.)
    /// </summary>
    bool IsFresh(int particle);

    /// <summary>
    /// Wakes the particle's island: from now on the context's inverse masses hold their values again (the same memory).
    /// Undone with the step if the step fails.
    /// </summary>
    void Wake(int particle);
}
