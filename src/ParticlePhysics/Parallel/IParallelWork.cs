namespace ParticlePhysics.Parallel;

/// <summary>
/// Work split into chunks that may run concurrently: the engine's parallel passes implement it, and a
/// <see cref="IParallelRunner"/> executes it. Each chunk touches only its own part of the output.
/// </summary>
public interface IParallelWork
{
    /// <summary>Executes chunk <paramref name="chunk"/> of <paramref name="chunkCount"/>.</summary>
    void Execute(int chunk, int chunkCount);
}
