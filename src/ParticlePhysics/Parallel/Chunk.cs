namespace ParticlePhysics.Parallel;

/// <summary>The half-open range [Start, End) of chunk c of n over a count of items, as even as integers allow.</summary>
internal static class Chunk
{
    public static (int Start, int End) Range(int chunk, int chunkCount, int count) =>
        ((int)((long)count * chunk / chunkCount), (int)((long)count * (chunk + 1) / chunkCount));
}
