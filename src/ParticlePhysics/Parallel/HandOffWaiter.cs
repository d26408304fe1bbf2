using System.Diagnostics;
using System.Threading;

namespace ParticlePhysics.Parallel;

/// <summary>
/// Where one thread of a <see cref="WorkerThreadRunner"/> waits for a hand-off (a worker for the next run, the caller
/// for the last chunk): it spins for at most the spin limit while spinning has been paying off, and otherwise sleeps
/// until another thread calls <see cref="Wake"/>. Exactly one thread waits on a given waiter.
/// </summary>
/// <remarks>
/// <para><b>Sleeping without losing a wake-up.</b> The waiter and its wakers share one flag, <c>_state</c>:
/// <c>Asleep</c> means "a waker must signal me", <c>Awake</c> means "nobody needs to". A waker first makes the
/// condition true with an interlocked operation (a full fence), then reads the flag, and only if it reads
/// <c>Asleep</c> swaps it to <c>Awake</c> (Interlocked.Exchange) and, if the swap returned <c>Asleep</c>, signals.
/// The waiter, to sleep, swaps the flag to <c>Asleep</c> (Interlocked.Exchange, a full fence), then tests the
/// condition again. Both sides write their variable and then read the other's with a full fence between, so at
/// least one of them sees the other's write (Dekker): either the waiter sees the condition true, or the waker sees
/// <c>Asleep</c> and signals. A wake-up cannot be lost.</para>
/// <para><b>Never a signal too many.</b> When the waiter sees the condition true after setting <c>Asleep</c>, it tries
/// to take the flag back (compare-exchange <c>Asleep</c> to <c>Awake</c>). If that succeeds no waker swapped it, so
/// no signal is coming and it returns. If it fails a waker did swap it, its signal is coming, and the waiter blocks
/// to consume it. A signal is sent only by the one waker whose swap returned <c>Asleep</c>, once per sleep, and every
/// sleep ends by consuming its signal or by taking the flag back: the signal (a flag under a lock, with
/// Monitor.Wait and Pulse) is never set twice, which the tests check through <see cref="DoubleSignals"/>.</para>
/// <para><b>Stale signals.</b> A waker may be slow: the runner's caller can see its run finished (the last chunk's
/// counter) and start the next run before the thread that finished that chunk has called <see cref="Wake"/>. That
/// late call may then find the caller asleep in the next run and signal it. So the waiter tests its condition after
/// every signal and sleeps again if it is false; a stale signal costs a wake-up, never a wrong result.</para>
/// <para><b>Whether to spin.</b> Spinning pays when the partner arrives within the spin limit; it costs the limit
/// in CPU time when it does not, and on a machine with more runnable threads than cores it takes the core that the
/// partner needs (a yield hands it over, but then the spinner waits for a core itself). Each wait therefore records
/// whether it paid: a spin that saw the condition come true within the limit did; a spin that ran out, or that lost
/// its core for longer than the limit (to a yield or a preemption), did not; a sleep would have (so the next wait
/// may try spinning) when the waker's signal came within the limit of the wait's start. A slow wake-up after a
/// prompt signal still counts as paid: it is what a spin would have saved. A score counts up by one for each wait
/// that paid, up to 16, and is halved by each that did not; the waiter spins while the score is at least 8. A quiet
/// machine opens the gate after 8 prompt hand-offs; two waits that did not pay close it, and 8 prompt ones in a row
/// are needed to open it again, so a busy machine, where the partner is often descheduled, sees few spins, the
/// way adaptive mutexes stop spinning on a lock whose holder is not running.</para>
/// </remarks>
internal sealed class HandOffWaiter
{
    private const int Awake = 0;
    private const int Asleep = 1;
    private const int ScoreLimit = 16;
    private const int SpinThreshold = 8;

    // Condition tests between two reads of the clock, and pauses between two tests: the condition is seen within a
    // pause or two, and the clock, dearer than a test, is read once every eight.
    private const int TestsPerClockRead = 8;
    private const int PausesPerTest = 2;

    private readonly object _lock = new();
    private readonly long _spinLimitTicks;
    private readonly long _yieldTicks;
    private readonly bool _adaptive;
    private int _state;
    private int _score;
    private bool _signalled;
    private long _signalledAt;

    /// <param name="spinLimitTicks">The longest spin, in <see cref="Stopwatch"/> ticks; 0: never spin.</param>
    /// <param name="adaptive">False: spin up to the limit on every wait, paid or not (for the tests).</param>
    public HandOffWaiter(long spinLimitTicks, bool adaptive)
    {
        _spinLimitTicks = spinLimitTicks;
        _adaptive = adaptive;
        // A spinner yields its core about four times per spin (at least every 10 us), so that a partner waiting for
        // that core gets it; no more often, since a yield is dear even when no other thread wants the core.
        _yieldTicks = System.Math.Min(spinLimitTicks / 4, Stopwatch.Frequency / 100_000) + 1;
    }

    /// <summary>A condition a waiter waits for. Once true it stays true until the waiter itself acts.</summary>
    public interface ICondition
    {
        /// <summary>Whether the hand-off has happened (a volatile or interlocked read).</summary>
        bool IsMet();
    }

    /// <summary>Sleeps that ended with a signal (for the tests).</summary>
    public long Signals { get; private set; }

    /// <summary>Signals sent while one was still pending: always 0 unless the protocol is broken (for the tests).</summary>
    public long DoubleSignals { get; private set; }

    /// <summary>Waits that spun (for the benchmarks and tests).</summary>
    public long Spins { get; private set; }

    /// <summary>Whether the next wait would spin first.</summary>
    public bool WouldSpin => _spinLimitTicks > 0 && (!_adaptive || _score >= SpinThreshold);

    /// <summary>Returns once <paramref name="condition"/> is true: spins first if spinning has been paying off.</summary>
    public void Wait<TCondition>(TCondition condition)
        where TCondition : struct, ICondition
    {
        if (condition.IsMet())
        {
            return; // no wait, nothing to learn
        }

        var start = Stopwatch.GetTimestamp();
        if (!WouldSpin)
        {
            Sleep(condition, start, learn: true);
            return;
        }

        Spins++;
        var paid = Spin(condition, start);
        Learn(paid);
        if (!paid)
        {
            Sleep(condition, start, learn: false);
        }
    }

    /// <summary>
    /// Signals the waiter if it sleeps or is about to. Call only after making its condition true with an interlocked
    /// operation (the full fence that the read of the flag below relies on).
    /// </summary>
    public void Wake()
    {
        // A plain read first: a waiter that is awake (spinning or running) costs the waker no interlocked operation.
        if (Volatile.Read(ref _state) != Asleep || Interlocked.Exchange(ref _state, Awake) != Asleep)
        {
            return;
        }

        var now = Stopwatch.GetTimestamp();
        lock (_lock)
        {
            if (_signalled)
            {
                DoubleSignals++;
            }

            _signalled = true;
            _signalledAt = now;
            Monitor.Pulse(_lock);
        }
    }

    /// <summary>
    /// Spins until the condition is true or the spin limit has passed; true if it came true within the limit (a spin
    /// that lost its core for longer, to a yield or a preemption, did not pay even if the condition is now true).
    /// </summary>
    private bool Spin<TCondition>(TCondition condition, long start)
        where TCondition : struct, ICondition
    {
        var lastYield = start;

        // Bounded: every TestsPerClockRead tests the clock is read, and the loop ends once the limit has passed.
        while (true)
        {
            for (var test = 0; test < TestsPerClockRead; test++)
            {
                if (condition.IsMet())
                {
                    return Stopwatch.GetTimestamp() - start <= _spinLimitTicks;
                }

                Thread.SpinWait(PausesPerTest);
            }

            var now = Stopwatch.GetTimestamp();
            if (now - start > _spinLimitTicks)
            {
                return false;
            }

            if (now - lastYield > _yieldTicks)
            {
                Thread.Yield();
                lastYield = now;
            }
        }
    }

    /// <summary>
    /// Sleeps until the condition is true; when <paramref name="learn"/>, records whether a spin would have paid.
    /// </summary>
    private void Sleep<TCondition>(TCondition condition, long start, bool learn)
        where TCondition : struct, ICondition
    {
        // Bounded by the signals received: each pass either returns or consumes one signal, and a signal is sent
        // only for a hand-off that made some condition of this waiter true.
        while (true)
        {
            Interlocked.Exchange(ref _state, Asleep);
            if (condition.IsMet() && Interlocked.CompareExchange(ref _state, Awake, Asleep) == Asleep)
            {
                // No waker swapped the flag, so none will signal: the hand-off came before the sleep did.
                if (learn)
                {
                    Learn(true);
                }

                return;
            }

            // Asleep and the condition false (a waker will signal), or a waker already swapped the flag (its signal
            // is coming): either way exactly one signal is ours to consume.
            long signalledAt;
            lock (_lock)
            {
                while (!_signalled)
                {
                    Monitor.Wait(_lock);
                }

                _signalled = false;
                signalledAt = _signalledAt;
                Signals++;
            }

            if (condition.IsMet())
            {
                if (learn)
                {
                    Learn(signalledAt - start <= _spinLimitTicks);
                }

                return;
            }

            // A stale signal (a slow waker of an earlier hand-off): sleep again.
        }
    }

    private void Learn(bool paid) => _score = paid ? System.Math.Min(_score + 1, ScoreLimit) : _score >> 1;
}
