namespace ParticlePhysics.Parallel;

/// <summary>The half-open range [Start, End) of chunk c of n over a count of items, as even as integers allow.</summary>
internal static class Chunk
{
    public static (int Start, int End) Range(int chunk, int chunkCount, int count) =>
        ((int)((long)count * chunk / chunkCount), (int)((long)count * (chunk + 1) / chunkCount));

    /// <summary>
    /// Runs the <paramref name="chunkCount"/> chunks of <paramref name="work"/> on the runner when it has threads to give,
    /// else in order on the calling thread: the chunks, hence the bits, are the same either way.
    /// </summary>
    public static void RunAll(IParallelRunner? runner, IParallelWork work, int chunkCount)
    {
        if (runner is { MaxParallelism: > 1 })
        {
            runner.Run(work, chunkCount);
            return;
        }

        for (var c = 0; c < chunkCount; c++)
        {
            work.Execute(c, chunkCount);
        }
    }

    /// <summary>The chunks' partial sums added in chunk order: the same bits whichever threads ran the chunks.</summary>
    public static double Sum(double[] partials)
    {
        var total = 0.0;
        for (var c = 0; c < partials.Length; c++)
        {
            total += partials[c];
        }

        return total;
    }
}
