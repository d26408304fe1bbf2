namespace ParticlePhysics.Demo.Running;

/// <summary>A run of particles (a scenario's or a scene's), as the replay and the cost estimate see it.</summary>
internal interface IParticleRun
{
    /// <summary>The number of particles.</summary>
    int ParticleCount { get; }

    /// <summary>n &gt; 1 when the particles are an n x n grid whose triangles the replay shades; 0 otherwise.</summary>
    int SurfaceSide { get; }

    /// <summary>The replay page's subtitle, or null for the run's parameters.</summary>
    string? Subtitle { get; }

    /// <summary>A fresh world at t = 0, as every run starts from (the replay reads its pins, links and colliders).</summary>
    ParticleWorld BuildWorld();
}
