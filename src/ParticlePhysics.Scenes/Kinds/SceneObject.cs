namespace ParticlePhysics.Scenes.Kinds;

/// <summary>
/// One checked object of a scene, ready to be built any number of times. The scene builds in two passes so that an
/// object may join particles listed after it: every object adds its particles (in list order, so particle numbers are
/// the contract's), then every object adds its springs, links and loads.
/// </summary>
internal abstract class SceneObject
{
    /// <summary>The particles it makes.</summary>
    public virtual int ParticleCount => 0;

    /// <summary>Checks its global particle indices against the scene's particle count (they are known only once every object is read).</summary>
    public virtual void CheckIndices(SceneIndexCheck check)
    {
    }

    /// <summary>Adds its particles to <see cref="SceneBuilder.World"/>.</summary>
    public virtual void AddParticles(SceneBuilder builder)
    {
    }

    /// <summary>Adds its springs, links and loads.</summary>
    public virtual void AddElements(SceneBuilder builder)
    {
    }
}

/// <summary>One checked collider, made anew for each build.</summary>
internal abstract class SceneCollider
{
    /// <summary>The kind's name, for the description of a scene.</summary>
    public abstract string Kind { get; }

    /// <summary>A new obstacle for one world.</summary>
    public abstract Contacts.Obstacle CreateObstacle();
}
