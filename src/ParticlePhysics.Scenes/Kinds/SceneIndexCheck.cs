namespace ParticlePhysics.Scenes.Kinds;

/// <summary>Checks particle indices against the scene's particle count, naming a bad one where it was written.</summary>
internal sealed class SceneIndexCheck
{
    public SceneIndexCheck(string file, int particleCount)
    {
        File = file;
        ParticleCount = particleCount;
    }

    public string File { get; }

    /// <summary>The scene's particles: indices run from 0 to this - 1.</summary>
    public int ParticleCount { get; }

    /// <summary>Refuses an index beyond the scene's particles.</summary>
    public void Particle(IndexRef index)
    {
        if (index.Value >= ParticleCount)
        {
            throw new SceneException(
                File,
                index.Path,
                index.Where.Line,
                index.Where.Column,
                index.Where.Text(),
                ParticleCount == 0
                    ? "names a particle, and the scene has none"
                    : $"names no particle: the scene's particles are numbered 0 to {ParticleCount - 1} in the order the objects list them");
        }
    }
}
