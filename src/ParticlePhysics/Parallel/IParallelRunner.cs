namespace ParticlePhysics.Parallel;

/// <summary>
/// Runs the chunks of an <see cref="IParallelWork"/> concurrently. The engine never starts threads of its own and
/// never uses a global pool: a host that wants both cores sets <see cref="ParticleWorld.Runner"/> to an
/// implementation of this interface, either <see cref="WorkerThreadRunner"/> or an adapter to its own job system.
/// Results are bit-identical with or without a runner, whatever the number of chunks or threads.
/// </summary>
/// <remarks>
/// The engine cuts the same particles into the same chunks pass after pass, so an adapter runs faster when it gives
/// a chunk to the same thread from one run to the next (as <see cref="WorkerThreadRunner"/> does: each thread first
/// takes its own share of the chunks), so that the chunk's data is still in that core's cache; which thread runs a
/// chunk never changes the results.
/// </remarks>
public interface IParallelRunner
{
    /// <summary>How many chunks can run at the same time (threads or job workers, the caller's included).</summary>
    int MaxParallelism { get; }

    /// <summary>
    /// Calls <c>work.Execute(i, chunkCount)</c> exactly once for every i in [0, chunkCount), possibly concurrently,
    /// and returns when all have finished. If a chunk throws, rethrows after the others have finished.
    /// Must not allocate per call (it runs several times per simulation step).
    /// </summary>
    void Run(IParallelWork work, int chunkCount);
}
