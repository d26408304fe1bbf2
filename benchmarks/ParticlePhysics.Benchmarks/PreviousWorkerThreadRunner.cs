using System;
using System.Runtime.ExceptionServices;
using System.Threading;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The baseline of the hand-off measurements: <c>WorkerThreadRunner</c> as it was until commit 7f70abb, kept
/// unchanged but for its name. The workers block on a semaphore between runs and the caller blocks on another
/// until every worker (not every chunk) has finished, so each run wakes a sleeping thread twice; the caller also
/// waits for a worker that got no core before the caller had run every chunk itself.
/// </summary>
internal sealed class PreviousWorkerThreadRunner : IParallelRunner, IDisposable
{
    private readonly Thread[] _threads;
    private readonly SemaphoreSlim _start = new(0);
    // The last worker to finish releases this. (A SemaphoreSlim creates its lock in its constructor; a
    // ManualResetEventSlim would allocate one the first time a wait blocks, in the middle of a simulation.)
    private readonly SemaphoreSlim _finished = new(0);
    private IParallelWork? _work;
    private int _chunkCount;
    private int _nextChunk;
    private int _busyWorkers;
    private ExceptionDispatchInfo? _failure;
    private volatile bool _disposed;

    /// <summary>Creates a runner with <paramref name="parallelism"/> - 1 worker threads (default: one per core).</summary>
    /// <param name="parallelism">The number of chunks run at once, the calling thread included: at least 1.</param>
    public PreviousWorkerThreadRunner(int parallelism = 0)
    {
        if (parallelism < 0)
        {
            throw new ArgumentOutOfRangeException(
                nameof(parallelism), parallelism, $"parallelism must be >= 1, or 0 for one per core; got {parallelism}.");
        }

        MaxParallelism = parallelism == 0 ? Environment.ProcessorCount : parallelism;
        _threads = new Thread[MaxParallelism - 1];
        for (var t = 0; t < _threads.Length; t++)
        {
            _threads[t] = new Thread(WorkerLoop) { IsBackground = true, Name = $"ParticlePhysics worker {t + 1}" };
            _threads[t].Start();
        }
    }

    /// <inheritdoc />
    public int MaxParallelism { get; }

    /// <inheritdoc />
    public void Run(IParallelWork work, int chunkCount)
    {
        // (Parallel is a leaf of the core, below the world's Guard: it checks its two arguments itself.)
        if (work is null)
        {
            throw new ArgumentNullException(nameof(work));
        }

        if (_disposed)
        {
            throw new ObjectDisposedException(nameof(PreviousWorkerThreadRunner));
        }

        if (chunkCount <= 0)
        {
            return;
        }

        if (_threads.Length == 0 || chunkCount == 1)
        {
            for (var chunk = 0; chunk < chunkCount; chunk++)
            {
                work.Execute(chunk, chunkCount);
            }

            return;
        }

        _work = work;
        _chunkCount = chunkCount;
        _nextChunk = 0;
        _failure = null;
        _busyWorkers = _threads.Length;
        _start.Release(_threads.Length);
        Drain(work, chunkCount);
        _finished.Wait();
        _work = null;
        _failure?.Throw();
    }

    /// <summary>Stops the worker threads.</summary>
    public void Dispose()
    {
        if (_disposed)
        {
            return;
        }

        _disposed = true;
        if (_threads.Length > 0)
        {
            _start.Release(_threads.Length); // (a runner of parallelism 1 has no worker to wake: Release(0) throws)
        }

        foreach (var thread in _threads)
        {
            thread.Join();
        }

        _start.Dispose();
        _finished.Dispose();
    }

    private void WorkerLoop()
    {
        while (true)
        {
            _start.Wait();
            if (_disposed)
            {
                return;
            }

            Drain(_work!, _chunkCount);
            if (Interlocked.Decrement(ref _busyWorkers) == 0)
            {
                _finished.Release();
            }
        }
    }

    private void Drain(IParallelWork work, int chunkCount)
    {
        int chunk;
        while ((chunk = Interlocked.Increment(ref _nextChunk) - 1) < chunkCount)
        {
            try
            {
                work.Execute(chunk, chunkCount);
            }
            catch (Exception ex)
            {
                Interlocked.CompareExchange(ref _failure, ExceptionDispatchInfo.Capture(ex), null);
            }
        }
    }
}
