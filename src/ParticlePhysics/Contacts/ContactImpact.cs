namespace ParticlePhysics.Contacts;

/// <summary>
/// One impact that a step resolved (<see cref="ContactSet.Impacts"/>): when, who, and how hard; what a game plays a
/// sound or spawns dust for.
/// </summary>
public readonly struct ContactImpact
{
    /// <summary>Creates a record; the contact set does this.</summary>
    public ContactImpact(double time, int particle, int other, bool withObstacle, double normalSpeed, bool resting)
    {
        Time = time;
        Particle = particle;
        Other = other;
        WithObstacle = withObstacle;
        NormalSpeed = normalSpeed;
        Resting = resting;
    }

    /// <summary>The time of the impact, in seconds (within the step, not its end).</summary>
    public double Time { get; }

    /// <summary>The particle (for a pair: the smaller index).</summary>
    public int Particle { get; }

    /// <summary>The obstacle's index in <see cref="ContactSet.Obstacles"/>, or the other particle.</summary>
    public int Other { get; }

    /// <summary>True for an impact with an obstacle, false between two particles.</summary>
    public bool WithObstacle { get; }

    /// <summary>The normal relative speed u at which they met, in m/s.</summary>
    public double NormalSpeed { get; }

    /// <summary>True when the rebound e u was below <see cref="ContactSet.RestingSpeed"/>: the particle came to rest instead.</summary>
    public bool Resting { get; }
}
