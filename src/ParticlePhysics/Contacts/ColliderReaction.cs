namespace ParticlePhysics.Contacts;

/// <summary>
/// What an obstacle received from the particles over a step (<see cref="ContactSet.ReactionOf"/>): for a host that
/// moves the obstacle as a body of its own, the change of momentum and of angular momentum the particles gave it.
/// </summary>
public readonly struct ColliderReaction
{
    /// <summary>Creates a reaction; the contact set does this.</summary>
    public ColliderReaction(Vector3d impulse, Vector3d angularImpulse)
    {
        Impulse = impulse;
        AngularImpulse = angularImpulse;
    }

    /// <summary>The total impulse on the obstacle, in N s: minus the momentum the contacts gave the particles.</summary>
    public Vector3d Impulse { get; }

    /// <summary>
    /// The angular impulse on the obstacle about its <see cref="Obstacle.ReactionPoint"/>, in N m s: the sum of
    /// (contact point - reaction point) x impulse over its contacts, each point where it was at the contact's time.
    /// </summary>
    public Vector3d AngularImpulse { get; }
}
