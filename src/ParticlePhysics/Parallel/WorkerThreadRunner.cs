using System;
using System.Diagnostics;
using System.Runtime.ExceptionServices;
using System.Threading;

namespace ParticlePhysics.Parallel;

/// <summary>
/// An <see cref="IParallelRunner"/> with its own dedicated background threads (the calling thread works too).
/// Create one per simulation thread, set it as <see cref="ParticleWorld.Runner"/>, and dispose it when done.
/// Each thread has a share of a run's chunks, the same share from one run to the next (the caller the first), and
/// takes the chunks of the others' shares once its own are done. Between runs a thread waiting for its partner spins
/// for a few microseconds while spinning has been paying off (a quiet machine: a hand-off then costs well under a
/// microsecond) and sleeps otherwise (a busy machine: the cost of waking a thread, a few microseconds, as with plain
/// blocking).
/// </summary>
/// <remarks>
/// <para><b>One run at a time.</b> <see cref="Run"/> and <see cref="Dispose"/> are called by one thread at a time,
/// the host's simulation thread; a second <see cref="Run"/> while one is in progress (from another thread, or from
/// inside a chunk) throws <see cref="InvalidOperationException"/>, as does <see cref="Dispose"/> during a run.</para>
/// <para><b>Shares.</b> With p threads (the caller is thread 0, worker t - 1 is thread t) and c chunks, thread t's
/// share is the chunks from ceil(t c / p) to ceil((t + 1) c / p). The engine's passes split the same particles into
/// the same chunks every time, so a thread that runs its own share finds its chunks' data where its last pass left
/// it, in its core's cache, where one counter shared by every thread would hand a chunk to whichever thread came first
/// (docs/benchmarks.md, "Shares of a run"). Results do not depend on it: a share decides who runs a chunk first, never
/// what it computes.</para>
/// <para><b>The protocol.</b> The shared state of a run is its work, its chunk count, the end of each share,
/// <c>_finished</c> (chunks done), <c>_failure</c> and, per share, one 64-bit claim word: the run's number in the high
/// 32 bits, the share's next unclaimed chunk in the low 32 (each word alone on its cache line).</para>
/// <list type="number">
/// <item>The caller first closes the previous run r - 1 in every share: <c>Interlocked.Exchange(word, (r - 1,
/// Closed))</c>, where Closed (int.MaxValue) is no chunk's index. It then writes the new work, count, share ends,
/// <c>_finished = 0</c> and <c>_failure = null</c> with plain writes, and opens run r in every share with
/// <c>Interlocked.Exchange(word, (r, the share's first chunk))</c>, a full fence: a thread that reads run number r from
/// a word sees those writes.</item>
/// <item>It then wakes, with <see cref="HandOffWaiter.Wake"/>, the workers whose shares have chunks (all of them
/// when the run has as many chunks as threads; with fewer, the owners of the chunks). A worker waits for its own
/// share's word to show a new run; a spinning worker needs no wake; see <see cref="HandOffWaiter"/> for why a wake-up
/// cannot be lost.</item>
/// <item>Every thread, the caller included, claims the chunks of its own share, then of the next shares in turn
/// (t + 1, t + 2, ... modulo p), by compare-exchange of the share's word from (r, i) to (r, i + 1), after reading
/// (r, i) and then the count, and the share's end above i. A word never takes the same value twice (the run number
/// grows, and within a run the index only grows until the run is closed), so a thread holding a stale value fails
/// its compare-exchange: a chunk is claimed once, and only for its own run. A claim that succeeds means the word held
/// (r, i) from the thread's read of it to its compare-exchange, so the count and end read in between were run r's
/// (the caller rewrites them only after closing every share of run r, which changes the word; without the close, a
/// thread that read (r, end of r) could read the next run's larger end and claim a chunk past the end of run r's
/// share). Run r cannot finish before its claimed chunk i does, so the work that the claimer reads after its claim
/// is run r's too. A thread leaves a share whose word shows another run than its own (not yet opened for run r, or
/// opened for a later one): what a worker leaves so, the caller takes, since it opens every share before it drains
/// any and visits every share.</item>
/// <item>After a chunk (whether it returned or threw; an exception is kept in <c>_failure</c> by compare-exchange, the
/// first one wins) the thread increments <c>_finished</c> (interlocked); the one that brings it to the count wakes
/// the caller if it waits.</item>
/// <item>The caller, after claiming chunks until no share has any left, waits until <c>_finished</c> equals the count,
/// then rethrows the failure if any. It opens every share before it drains any and visits every share, so every
/// chunk is claimed even if no worker ever runs; it never waits for a worker that has no chunk: a worker that is
/// descheduled before it claims anything costs the run nothing, and finds, when it runs again, either the next run
/// or nothing to claim.</item>
/// </list>
/// <para>(The run number wraps after 2^32 runs: a stale value could match again only for a thread stalled between its
/// read and its compare-exchange for 2^32 runs. A torn read of a word, on a platform where a 64-bit read is
/// not atomic, gives a value that fails the compare-exchange or ends the thread's draining of that share early: never
/// a wrong claim.)</para>
/// <para>Nothing is allocated per run on any thread: the waiters, their locks, the words and the threads are created
/// here, and a run only writes fields. Results do not depend on this class: it decides which thread runs a chunk,
/// never what a chunk computes.</para>
/// </remarks>
public sealed class WorkerThreadRunner : IParallelRunner, IDisposable
{
    /// <summary>
    /// The spin limit of <see cref="WorkerThreadRunner(int)"/>: 200 microseconds, longer than the serial work between
    /// the engine's passes on a large cloth, so that a worker is still awake for the next pass, and a few times what
    /// waking a sleeping thread costs on a virtual machine (docs/architecture.md, Parallelism).
    /// </summary>
    public static readonly TimeSpan DefaultSpinLimit = TimeSpan.FromTicks(2000);

    /// <summary>The longest spin limit accepted: 1 ms, about a scheduler time slice.</summary>
    public static readonly TimeSpan MaximumSpinLimit = TimeSpan.FromMilliseconds(1);

    // The chunk index of a closed run: no chunk has it (counts are at most int.MaxValue, indices below).
    private const long Closed = int.MaxValue;

    // Share t's claim word is _claims[WordStride * (t + 1)]: 64 bytes apart, and apart from the array's header, so that
    // no two words, nor a word and another object, share a cache line.
    private const int WordStride = 8;

    private readonly Thread[] _threads;
    private readonly HandOffWaiter[] _workers;
    private readonly HandOffWaiter _caller;
    private readonly long[] _claims;
    private readonly int[] _shareEnds;
    private IParallelWork? _work;
    private int _chunkCount;
    private int _finished;
    private ExceptionDispatchInfo? _failure;
    private uint _run;
    private int _inRun;
    private int _disposed;

    /// <summary>
    /// Creates a runner with <paramref name="parallelism"/> - 1 worker threads (default: one per core) and the
    /// <see cref="DefaultSpinLimit"/>.
    /// </summary>
    /// <param name="parallelism">The number of chunks run at once, the calling thread included: at least 1.</param>
    public WorkerThreadRunner(int parallelism = 0)
        : this(parallelism, DefaultSpinLimit)
    {
    }

    /// <summary>Creates a runner with <paramref name="parallelism"/> - 1 worker threads and a spin limit.</summary>
    /// <param name="parallelism">The number of chunks run at once, the calling thread included: at least 1, or 0
    /// for one per core.</param>
    /// <param name="spinLimit">The longest a waiting thread spins before it sleeps, when spinning has been paying
    /// off; <see cref="TimeSpan.Zero"/>: never spin (every hand-off wakes a sleeping thread). At most
    /// <see cref="MaximumSpinLimit"/>.</param>
    public WorkerThreadRunner(int parallelism, TimeSpan spinLimit)
        : this(parallelism, spinLimit, adaptive: true)
    {
    }

    /// <summary>The constructor of the public ones; <paramref name="adaptive"/> false spins on every wait (for the tests).</summary>
    internal WorkerThreadRunner(int parallelism, TimeSpan spinLimit, bool adaptive)
    {
        if (parallelism < 0)
        {
            throw new ArgumentOutOfRangeException(
                nameof(parallelism), parallelism, $"parallelism must be >= 1, or 0 for one per core; got {parallelism}.");
        }

        if (spinLimit < TimeSpan.Zero || spinLimit > MaximumSpinLimit)
        {
            throw new ArgumentOutOfRangeException(
                nameof(spinLimit), spinLimit, $"spinLimit must be between 0 and {MaximumSpinLimit.TotalMilliseconds} ms; got {spinLimit.TotalMilliseconds} ms.");
        }

        MaxParallelism = parallelism == 0 ? Environment.ProcessorCount : parallelism;
        SpinLimit = spinLimit;
        var spinTicks = (long)Math.Round(spinLimit.TotalSeconds * Stopwatch.Frequency);
        _caller = new HandOffWaiter(spinTicks, adaptive);
        _claims = new long[WordStride * (MaxParallelism + 1)];
        _shareEnds = new int[MaxParallelism];
        _workers = new HandOffWaiter[MaxParallelism - 1];
        _threads = new Thread[MaxParallelism - 1];
        for (var t = 0; t < _threads.Length; t++)
        {
            _workers[t] = new HandOffWaiter(spinTicks, adaptive);
            _threads[t] = new Thread(WorkerLoop) { IsBackground = true, Name = $"ParticlePhysics worker {t + 1}" };
            _threads[t].Start(t + 1);
        }
    }

    /// <inheritdoc />
    public int MaxParallelism { get; }

    /// <summary>The longest a waiting thread spins before it sleeps (zero: it never spins).</summary>
    public TimeSpan SpinLimit { get; }

    /// <summary>How many times the waiting threads slept and were signalled (for the tests and benchmarks).</summary>
    internal long Sleeps => SumOverWaiters(w => w.Signals);

    /// <summary>How many times worker <paramref name="worker"/> (share worker + 1) slept and was signalled (for the tests).</summary>
    internal long WorkerSignals(int worker) => _workers[worker].Signals;

    /// <summary>Signals sent twice to a waiter: 0 unless the hand-off protocol is broken (for the tests).</summary>
    internal long DoubleSignals => SumOverWaiters(w => w.DoubleSignals);

    /// <summary>How many waits spun first (for the tests and benchmarks).</summary>
    internal long SpinningWaits => SumOverWaiters(w => w.Spins);

    /// <inheritdoc />
    public void Run(IParallelWork work, int chunkCount)
    {
        // (Parallel is a leaf of the core, below the world's Guard: it checks its two arguments itself.)
        if (work is null)
        {
            throw new ArgumentNullException(nameof(work));
        }

        if (Volatile.Read(ref _disposed) != 0)
        {
            throw new ObjectDisposedException(nameof(WorkerThreadRunner));
        }

        if (chunkCount <= 0)
        {
            return;
        }

        if (Interlocked.Exchange(ref _inRun, 1) != 0)
        {
            throw new InvalidOperationException(
                "WorkerThreadRunner.Run was called while a run was in progress (from another thread, or from inside a chunk); it runs one at a time.");
        }

        try
        {
            if (_threads.Length == 0 || chunkCount == 1)
            {
                RunHere(work, chunkCount);
            }
            else
            {
                RunOnThreads(work, chunkCount);
            }
        }
        finally
        {
            Volatile.Write(ref _inRun, 0);
        }
    }

    /// <summary>Stops the worker threads and waits for them. Not during a run; a second call does nothing.</summary>
    public void Dispose()
    {
        if (Volatile.Read(ref _inRun) != 0)
        {
            throw new InvalidOperationException("WorkerThreadRunner.Dispose was called during a run.");
        }

        // The interlocked exchange is the fence Wake relies on: a worker either sees the flag or is signalled.
        if (Interlocked.Exchange(ref _disposed, 1) != 0)
        {
            return;
        }

        foreach (var worker in _workers)
        {
            worker.Wake();
        }

        foreach (var thread in _threads)
        {
            thread.Join();
        }
    }

    /// <summary>The chunks in order on the calling thread; a failure is rethrown after the others, as on threads.</summary>
    private static void RunHere(IParallelWork work, int chunkCount)
    {
        ExceptionDispatchInfo? failure = null;
        for (var chunk = 0; chunk < chunkCount; chunk++)
        {
            try
            {
                work.Execute(chunk, chunkCount);
            }
            catch (Exception ex) when (failure is null)
            {
                failure = ExceptionDispatchInfo.Capture(ex);
            }
            catch (Exception)
            {
                // A later failure: the first one is rethrown.
            }
        }

        failure?.Throw();
    }

    private void RunOnThreads(IParallelWork work, int chunkCount)
    {
        // Close the previous run in every share before touching its fields: from here on no claim of it can succeed
        // (see DrainShare). Each word keeps the run's number, so that no worker takes the closed run for a new one.
        var shares = _shareEnds.Length;
        var closed = ((long)_run << 32) | Closed;
        for (var t = 0; t < shares; t++)
        {
            Interlocked.Exchange(ref _claims[Word(t)], closed);
        }

        var run = unchecked(++_run);
        _work = work;
        _chunkCount = chunkCount;
        _finished = 0;
        _failure = null;
        for (var t = 0; t < shares; t++)
        {
            _shareEnds[t] = ShareStart(t + 1, chunkCount);
        }

        for (var t = 0; t < shares; t++)
        {
            // Open it (each exchange a full fence: a claimer that reads the run's number sees the fields above).
            Interlocked.Exchange(ref _claims[Word(t)], ((long)run << 32) | (uint)(t == 0 ? 0 : _shareEnds[t - 1]));
        }

        // Wake the owners of the other shares that have chunks (every worker unless the run has fewer chunks than
        // threads); the others sleep on, or take chunks of other shares if they are spinning anyway.
        for (var t = 0; t < _workers.Length; t++)
        {
            if (_shareEnds[t] < _shareEnds[t + 1]) // (share t + 1 runs from the end of share t to its own end)
            {
                _workers[t].Wake();
            }
        }

        Drain(run, 0);
        _caller.Wait(new RunFinished(this, chunkCount));

        // Every chunk has been claimed and finished: no thread can read the work any more (a claim would fail).
        _work = null;
        var failure = _failure;
        _failure = null;
        failure?.Throw();
    }

    private void WorkerLoop(object? state)
    {
        var share = (int)state!;
        var waiter = _workers[share - 1];
        uint seen = 0;
        while (true)
        {
            waiter.Wait(new NextRun(this, share, seen));
            if (Volatile.Read(ref _disposed) != 0)
            {
                return;
            }

            seen = RunNumber(Volatile.Read(ref _claims[Word(share)]));
            Drain(seen, share);
        }
    }

    /// <summary>
    /// Claims and executes chunks of run <paramref name="run"/>: those of share <paramref name="own"/>, then of the
    /// shares after it in turn, until none is left, the run is over, or a later run began.
    /// </summary>
    private void Drain(uint run, int own)
    {
        var shares = _shareEnds.Length;
        for (var k = 0; k < shares; k++)
        {
            var share = own + k < shares ? own + k : own + k - shares;
            if (!DrainShare(run, share))
            {
                return;
            }
        }
    }

    /// <summary>
    /// Claims and executes chunks of run <paramref name="run"/> in share <paramref name="share"/> until the share has
    /// none left for this run or shows another run (true), or this thread finished the run's last chunk (false:
    /// nothing is left anywhere).
    /// </summary>
    private bool DrainShare(uint run, int share)
    {
        // Bounded: each pass claims a chunk, or finds the share empty or in another run, or fails a compare-exchange
        // because the word changed meanwhile (another thread's claim, at most chunkCount per run, or the caller's
        // close or open of a run, after which the next pass returns).
        ref var word = ref _claims[Word(share)];
        while (true)
        {
            var claim = Volatile.Read(ref word);
            var chunk = (int)(uint)claim;
            var chunkCount = Volatile.Read(ref _chunkCount);
            var end = Volatile.Read(ref _shareEnds[share]);
            if (RunNumber(claim) != run || chunk >= end)
            {
                return true;
            }

            if (Interlocked.CompareExchange(ref word, claim + 1, claim) != claim)
            {
                continue;
            }

            // Claimed: the word held (run, chunk) from the read above to here, so the count and end read in between
            // are this run's (the caller rewrites them only after closing every share, which changes the word), and
            // the run cannot finish before this chunk does, so the work read below is this run's too.
            try
            {
                _work!.Execute(chunk, chunkCount);
            }
            catch (Exception ex)
            {
                Interlocked.CompareExchange(ref _failure, ExceptionDispatchInfo.Capture(ex), null);
            }

            if (Interlocked.Increment(ref _finished) == chunkCount)
            {
                _caller.Wake(); // (a no-op when the caller itself finished the run: it is not asleep)
                return false;
            }
        }
    }

    /// <summary>The first chunk of share <paramref name="share"/> (share p: the count), ceil(share c / p).</summary>
    private int ShareStart(int share, int chunkCount) =>
        (int)((((long)share * chunkCount) + _shareEnds.Length - 1) / _shareEnds.Length);

    private static int Word(int share) => WordStride * (share + 1);

    /// <summary>A counter summed over the caller's waiter and every worker's (diagnostics, not the hand-off path).</summary>
    private long SumOverWaiters(Func<HandOffWaiter, long> counter)
    {
        var sum = counter(_caller);
        foreach (var worker in _workers)
        {
            sum += counter(worker);
        }

        return sum;
    }

    private static uint RunNumber(long claim) => (uint)(claim >>> 32);

    /// <summary>
    /// A worker's wait: its share's word shows a run other than the last one it saw (the caller opens every share of a
    /// run before it wakes anyone), or the runner is disposed.
    /// </summary>
    private readonly struct NextRun : HandOffWaiter.ICondition
    {
        private readonly WorkerThreadRunner _runner;
        private readonly int _share;
        private readonly uint _seen;

        public NextRun(WorkerThreadRunner runner, int share, uint seen)
        {
            _runner = runner;
            _share = share;
            _seen = seen;
        }

        public bool IsMet() =>
            RunNumber(Volatile.Read(ref _runner._claims[Word(_share)])) != _seen || Volatile.Read(ref _runner._disposed) != 0;
    }

    /// <summary>The caller's wait: every chunk of the run has finished.</summary>
    private readonly struct RunFinished : HandOffWaiter.ICondition
    {
        private readonly WorkerThreadRunner _runner;
        private readonly int _chunkCount;

        public RunFinished(WorkerThreadRunner runner, int chunkCount)
        {
            _runner = runner;
            _chunkCount = chunkCount;
        }

        public bool IsMet() => Volatile.Read(ref _runner._finished) == _chunkCount;
    }
}
