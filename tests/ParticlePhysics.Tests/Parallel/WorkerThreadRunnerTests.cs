using System;
using System.Diagnostics;
using System.Linq;
using System.Threading;
using ParticlePhysics.Parallel;
using Xunit.Abstractions;

namespace ParticlePhysics.Tests.Parallel;

/// <summary>
/// The runner's hand-off protocol: every chunk exactly once per run whatever the timing, no lost wake-up (a run that
/// needs every worker at once completes), no signal sent twice, failures rethrown after the other chunks, and the
/// edges (parallelism 1, chunk counts 0 and 1, disposal, misuse). Each stress test runs for about a second, and for
/// at least a fixed number of runs however long they take (a loaded machine gives fewer runs per second: 821 instead
/// of some 60 000 in a second, seen while two other processes kept both cores busy), with a watchdog that fails it,
/// rather than hanging, if a run never returns.
/// </summary>
public class WorkerThreadRunnerTests
{
    private static readonly TimeSpan _budget = TimeSpan.FromSeconds(1);
    private static readonly TimeSpan _watchdog = TimeSpan.FromSeconds(60);
    private readonly ITestOutputHelper _output;

    public WorkerThreadRunnerTests(ITestOutputHelper output)
    {
        _output = output;
    }

    /// <summary>The runner as shipped, one that never spins, and one that always spins for 1 us then sleeps.</summary>
    public static TheoryData<int, string> Configurations()
    {
        var data = new TheoryData<int, string>();
        foreach (var parallelism in new[] { 2, 3, 4 })
        {
            foreach (var mode in new[] { "adaptive", "never-spin", "always-spin-1us" })
            {
                data.Add(parallelism, mode);
            }
        }

        return data;
    }

    [Theory]
    [MemberData(nameof(Configurations))]
    public void Every_chunk_runs_exactly_once_over_many_runs_of_random_sizes_and_timings(int parallelism, string mode)
    {
        using var runner = Create(parallelism, mode);
        var work = new CheckedWork(64);
        var random = new Random(parallelism * 31 + mode.Length);
        long runs = 0, chunks = 0;
        WithWatchdog(() =>
        {
            var clock = Stopwatch.StartNew();
            while ((clock.Elapsed < _budget || runs < 1000) && runs < 2_000_000)
            {
                // Mostly tiny runs of a few chunks; now and then more chunks than threads, 0 or 1 chunk, chunks that
                // pause, yield or sleep, and pauses between runs on either side of the spin limit.
                var roll = random.Next(100);
                var chunkCount = roll < 5 ? random.Next(2) : roll < 90 ? random.Next(2, 2 * parallelism + 1) : random.Next(2, 64);
                work.Delay = random.Next(100) switch
                {
                    < 70 => 0,
                    < 95 => random.Next(1, 200),
                    < 99 => -1,
                    _ => -2,
                };
                work.Expect(chunkCount);
                runner.Run(work, chunkCount);
                work.Check(chunkCount, runs);
                runs++;
                chunks += chunkCount;
                Pause(random);
            }
        });

        Assert.Equal(0, runner.DoubleSignals);
        _output.WriteLine($"{parallelism} threads, {mode}: {runs} runs, {chunks} chunks, {runner.Sleeps} sleeps, {runner.SpinningWaits} spinning waits");
    }

    [Theory]
    [InlineData(2)]
    [InlineData(3)]
    [InlineData(4)]
    public void Millions_of_tiny_runs_run_every_chunk_exactly_once(int parallelism)
    {
        // The shipped runner at full tilt: runs of 1 to 2p + 1 chunks of a few hundred nanoseconds each, back to
        // back (the workers keep spinning, and take chunks while the caller does), with a 1 ms sleep now and then.
        using var runner = new WorkerThreadRunner(parallelism);
        var work = new CheckedWork(64) { Delay = 8 };
        var seed = (uint)parallelism;
        long runs = 0;
        WithWatchdog(() =>
        {
            var clock = Stopwatch.StartNew();
            while ((clock.Elapsed < _budget || runs < 1000) && runs < 5_000_000)
            {
                seed = unchecked((seed * 1664525u) + 1013904223u);
                var chunkCount = 1 + (int)((seed >> 16) % (uint)((2 * parallelism) + 1));
                work.Expect(chunkCount);
                runner.Run(work, chunkCount);
                work.Check(chunkCount, runs);
                if (++runs % 100_000 == 0)
                {
                    Thread.Sleep(1);
                }
            }
        });

        Assert.Equal(0, runner.DoubleSignals);
        _output.WriteLine($"{parallelism} threads: {runs} runs, {runner.Sleeps} sleeps, {runner.SpinningWaits} spinning waits");
    }

    [Theory]
    [MemberData(nameof(Configurations))]
    public void Every_worker_wakes_for_a_run_that_needs_all_of_them_at_once(int parallelism, string mode)
    {
        // Each chunk waits until all the run's chunks are running at the same time, so the caller cannot take them
        // all: a worker whose wake-up was lost leaves the run stuck, and its chunks time out.
        using var runner = Create(parallelism, mode);
        var work = new RendezvousWork(parallelism);
        var random = new Random(parallelism * 17 + mode.Length);
        var runs = 0;
        WithWatchdog(() =>
        {
            var clock = Stopwatch.StartNew();
            while ((clock.Elapsed < _budget || runs < 100) && runs < 100_000)
            {
                work.Reset();
                runner.Run(work, parallelism);
                runs++;
                Pause(random);
            }
        });

        Assert.Equal(0, runner.DoubleSignals);
        _output.WriteLine($"{parallelism} threads, {mode}: {runs} runs, {runner.Sleeps} sleeps, {runner.SpinningWaits} spinning waits");
    }

    [Theory]
    [MemberData(nameof(Configurations))]
    public void Each_thread_runs_the_chunks_of_its_own_share_first_so_a_chunk_keeps_its_thread_from_run_to_run(int parallelism, string mode)
    {
        // A run of p chunks that must all run at once (each waits for the others), so that no thread can take a
        // second chunk before every chunk has a thread: each thread takes the first chunk of its own share, chunk t for
        // thread t, the caller chunk 0. So chunk t runs on the same thread in every run, the cache locality that the
        // shares are for (a shared counter gives a chunk to whichever thread comes first).
        using var runner = Create(parallelism, mode);
        var work = new RendezvousWork(parallelism);
        var first = new int[parallelism];
        var caller = 0;
        WithWatchdog(() =>
        {
            caller = Environment.CurrentManagedThreadId;
            var random = new Random(parallelism * 7 + mode.Length);
            for (var run = 0; run < 50; run++)
            {
                work.Reset();
                runner.Run(work, parallelism);
                if (run == 0)
                {
                    work.Threads.CopyTo(first, 0);
                }

                Assert.Equal(first, work.Threads);
                Pause(random);
            }
        });

        Assert.Equal(caller, first[0]);
        Assert.Equal(parallelism, first.Distinct().Count());
    }

    [Theory]
    [InlineData(4, 2)]
    [InlineData(4, 3)]
    [InlineData(5, 3)]
    public void With_fewer_chunks_than_threads_only_the_owners_of_the_chunks_are_woken(int parallelism, int chunks)
    {
        // A runner that never spins, so that its workers sleep between runs and each wake-up is a signal they count.
        // Runs of c < p chunks (share t: chunks ceil(t c / p) to ceil((t + 1) c / p), some of them empty) wake the
        // workers whose shares hold chunks, never the others, which are therefore signalled nothing, whatever the
        // timing. (Waking the first c - 1 workers instead, as a runner with one shared counter may, wakes the wrong
        // ones: for 4 threads and 2 chunks worker 1, whose share is empty, rather than worker 2, which owns chunk 1.)
        using var runner = Create(parallelism, "never-spin");
        var work = new CheckedWork(64);
        var owns = new bool[parallelism - 1];
        long[] before = new long[parallelism - 1];
        WithWatchdog(() =>
        {
            // First a run that needs every thread at once: every worker has woken, and counted its signal, when it ends.
            runner.Run(new RendezvousWork(parallelism), parallelism);
            for (var t = 0; t < owns.Length; t++)
            {
                owns[t] = ShareStart(t + 1, chunks, parallelism) < ShareStart(t + 2, chunks, parallelism);
                before[t] = runner.WorkerSignals(t);
            }

            for (var run = 1; run <= 50; run++)
            {
                work.Expect(chunks);
                runner.Run(work, chunks);
                work.Check(chunks, run);
                Thread.Sleep(1); // the workers go back to sleep
            }
        });

        Assert.Equal(chunks - 1, owns.Count(owner => owner));
        for (var t = 0; t < owns.Length; t++)
        {
            if (!owns[t])
            {
                Assert.True(before[t] == runner.WorkerSignals(t), $"worker {t} (share {t + 1}, no chunk of {chunks}) was woken {runner.WorkerSignals(t) - before[t]} times");
            }
        }
    }

    private static int ShareStart(int share, int chunks, int parallelism) =>
        (int)((((long)share * chunks) + parallelism - 1) / parallelism);

    [Theory]
    [InlineData(1)]
    [InlineData(3)]
    public void A_failing_chunk_is_rethrown_after_every_other_chunk_has_finished(int parallelism)
    {
        using var runner = new WorkerThreadRunner(parallelism);
        var work = new FailingWork(64, failing: new[] { 5, 40 });
        var ex = Assert.Throws<InvalidOperationException>(() => runner.Run(work, 64));
        Assert.Matches("^chunk (5|40)$", ex.Message);
        for (var chunk = 0; chunk < 64; chunk++)
        {
            Assert.Equal(chunk is 5 or 40 ? 0 : 1, work.Done[chunk]);
        }

        // Still usable, and a run without failures does not rethrow the old one.
        var counting = new CheckedWork(64);
        counting.Expect(64);
        runner.Run(counting, 64);
        counting.Check(64, 0);
    }

    [Fact]
    public void Parallelism_1_runs_every_chunk_in_order_on_the_calling_thread()
    {
        using var runner = new WorkerThreadRunner(1);
        Assert.Equal(1, runner.MaxParallelism);
        var work = new RecordingWork(10);
        runner.Run(work, 10);
        Assert.Equal(new[] { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9 }, work.Order);
        Assert.All(work.Threads, id => Assert.Equal(Environment.CurrentManagedThreadId, id));
    }

    [Theory]
    [InlineData(0)]
    [InlineData(1)]
    public void No_chunk_or_one_chunk_runs_on_the_calling_thread(int chunkCount)
    {
        using var runner = new WorkerThreadRunner(3);
        var work = new RecordingWork(1);
        runner.Run(work, chunkCount);
        Assert.Equal(chunkCount, work.Calls);
        Assert.All(work.Threads[..chunkCount], id => Assert.Equal(Environment.CurrentManagedThreadId, id));
        runner.Run(work, -1); // a negative count is no chunk, as before
        Assert.Equal(chunkCount, work.Calls);
    }

    [Fact]
    public void A_run_from_inside_a_chunk_or_from_a_second_thread_and_a_dispose_during_a_run_are_refused()
    {
        using var runner = new WorkerThreadRunner(2);
        var nested = new CallbackWork(chunk =>
        {
            if (chunk == 0)
            {
                runner.Run(new RecordingWork(2), 2);
            }
        });
        var ex = Assert.Throws<InvalidOperationException>(() => runner.Run(nested, 2));
        Assert.Contains("one at a time", ex.Message, StringComparison.Ordinal);

        Exception? fromOtherThread = null;
        var concurrent = new CallbackWork(chunk =>
        {
            if (chunk == 0)
            {
                var other = new Thread(() => fromOtherThread = Record(() => runner.Run(new RecordingWork(2), 2)));
                other.Start();
                other.Join();
            }
        });
        runner.Run(concurrent, 2);
        Assert.IsType<InvalidOperationException>(fromOtherThread);

        var disposing = new CallbackWork(chunk =>
        {
            if (chunk == 1)
            {
                runner.Dispose();
            }
        });
        Assert.Throws<InvalidOperationException>(() => runner.Run(disposing, 2));

        // None of that broke it.
        var counting = new CheckedWork(64);
        counting.Expect(40);
        runner.Run(counting, 40);
        counting.Check(40, 0);
    }

    [Theory]
    [InlineData(1)]
    [InlineData(2)]
    [InlineData(4)]
    public void Dispose_stops_idle_workers_after_failures_and_a_second_dispose_does_nothing(int parallelism)
    {
        WithWatchdog(() =>
        {
            // Idle long enough for every worker to have gone to sleep.
            var idle = new WorkerThreadRunner(parallelism);
            idle.Run(new RecordingWork(8), 8);
            Thread.Sleep(50);
            idle.Dispose();
            idle.Dispose();
            Assert.Throws<ObjectDisposedException>(() => idle.Run(new RecordingWork(4), 4));

            // Right after a run (workers spinning), and after runs that failed.
            var failed = new WorkerThreadRunner(parallelism, WorkerThreadRunner.MaximumSpinLimit);
            for (var i = 0; i < 3; i++)
            {
                Assert.Throws<InvalidOperationException>(() => failed.Run(new FailingWork(16, failing: new[] { 0, 15 }), 16));
            }

            failed.Dispose();
            Assert.Equal(0, failed.DoubleSignals);
        });
    }

    [Fact]
    public void A_spin_limit_of_zero_never_spins_and_limits_out_of_range_are_refused()
    {
        using var runner = new WorkerThreadRunner(2, TimeSpan.Zero);
        Assert.Equal(TimeSpan.Zero, runner.SpinLimit);
        var work = new CheckedWork(8);
        for (var i = 0; i < 2000; i++)
        {
            work.Expect(4);
            runner.Run(work, 4);
            work.Check(4, i);
        }

        Assert.Equal(0, runner.SpinningWaits);
        Assert.Equal(WorkerThreadRunner.DefaultSpinLimit, new WorkerThreadRunner(1).SpinLimit);
        Assert.Throws<ArgumentOutOfRangeException>("spinLimit", () => new WorkerThreadRunner(2, TimeSpan.FromTicks(-1)));
        Assert.Throws<ArgumentOutOfRangeException>("spinLimit", () => new WorkerThreadRunner(2, WorkerThreadRunner.MaximumSpinLimit + TimeSpan.FromTicks(1)));
    }

    [Fact]
    public void A_waiter_starts_spinning_when_its_partner_is_prompt_and_stops_when_it_is_late()
    {
        WithWatchdog(() =>
        {
            // Prompt: the hand-off happens between the waiter's first look and its decision to sleep (the condition
            // is false once, then true), which is within any spin limit.
            var waiter = new HandOffWaiter(Stopwatch.Frequency / 50_000, adaptive: true);
            Assert.False(waiter.WouldSpin);
            var prompt = new Flag { Value = 1 };
            for (var i = 0; i < 8; i++)
            {
                prompt.FalseReads = 1;
                waiter.Wait(new FlagSet(prompt));
            }

            Assert.True(waiter.WouldSpin);

            // Late: the partner comes 50 ms after the wait begins, far beyond the 20 us limit: the spin runs out, the
            // waiter sleeps, and the gate closes; a second late wait, which sleeps at once, keeps it closed.
            var late = new Flag();
            for (var i = 0; i < 2; i++)
            {
                late.Value = 0;
                var partner = new Thread(() =>
                {
                    Thread.Sleep(50);
                    Interlocked.Exchange(ref late.Value, 1);
                    waiter.Wake();
                });
                partner.Start();
                waiter.Wait(new FlagSet(late));
                partner.Join();
                Assert.False(waiter.WouldSpin);
            }

            Assert.Equal(1, waiter.Spins);
            Assert.Equal(0, waiter.DoubleSignals);
        });
    }

    internal static WorkerThreadRunner Create(int parallelism, string mode) => mode switch
    {
        "adaptive" => new WorkerThreadRunner(parallelism),
        "never-spin" => new WorkerThreadRunner(parallelism, TimeSpan.Zero),
        "always-spin-1us" => new WorkerThreadRunner(parallelism, TimeSpan.FromTicks(10), adaptive: false),
        _ => throw new ArgumentException(mode, nameof(mode)),
    };

    /// <summary>Between runs: mostly nothing, else a pause, a yield, or (rarely) a sleep long enough for workers to sleep.</summary>
    internal static void Pause(Random random)
    {
        switch (random.Next(1000))
        {
            case < 600:
                break;
            case < 900:
                Thread.SpinWait(random.Next(1, 400));
                break;
            case < 990:
                Thread.Yield();
                break;
            case < 998:
                Thread.Sleep(0);
                break;
            default:
                Thread.Sleep(1);
                break;
        }
    }

    /// <summary>Runs <paramref name="body"/> on a thread of its own and fails if it has not returned within a minute.</summary>
    private static void WithWatchdog(Action body)
    {
        Exception? failure = null;
        var thread = new Thread(() => failure = Record(body)) { IsBackground = true };
        thread.Start();
        Assert.True(thread.Join(_watchdog), "a run never returned: a lost wake-up");
        if (failure is not null)
        {
            System.Runtime.ExceptionServices.ExceptionDispatchInfo.Capture(failure).Throw();
        }
    }

    private static Exception? Record(Action action)
    {
        try
        {
            action();
            return null;
        }
        catch (Exception ex)
        {
            return ex;
        }
    }

    /// <summary>Counts each chunk's calls and checks the chunk count it is given; optional delays inside chunks.</summary>
    private sealed class CheckedWork : IParallelWork
    {
        private readonly int[] _calls;
        private int _expectedCount;
        private int _wrongCount;

        public CheckedWork(int capacity)
        {
            _calls = new int[capacity];
        }

        /// <summary>0: none; positive: Thread.SpinWait of that many; -1: Thread.Yield; -2: Thread.Sleep(0).</summary>
        public int Delay { get; set; }

        public void Expect(int chunkCount) => _expectedCount = chunkCount;

        public void Execute(int chunk, int chunkCount)
        {
            if (chunkCount != _expectedCount)
            {
                Interlocked.Increment(ref _wrongCount);
            }

            switch (Delay)
            {
                case > 0:
                    Thread.SpinWait(Delay);
                    break;
                case -1:
                    Thread.Yield();
                    break;
                case -2:
                    Thread.Sleep(0);
                    break;
            }

            Interlocked.Increment(ref _calls[chunk]);
        }

        /// <summary>Each chunk of the run exactly once, no other; resets the counts.</summary>
        public void Check(int chunkCount, long run)
        {
            Assert.True(_wrongCount == 0, $"run {run}: a chunk was given the wrong chunk count");
            for (var chunk = 0; chunk < _calls.Length; chunk++)
            {
                var expected = chunk < chunkCount ? 1 : 0;
                if (_calls[chunk] != expected)
                {
                    Assert.Fail($"run {run} of {chunkCount} chunks: chunk {chunk} ran {_calls[chunk]} times");
                }

                _calls[chunk] = 0;
            }
        }
    }

    /// <summary>Every chunk waits until all are running at once (10 s at most, then it throws); notes its thread.</summary>
    private sealed class RendezvousWork : IParallelWork
    {
        private readonly int _parties;
        private int _arrived;

        public RendezvousWork(int parties)
        {
            _parties = parties;
            Threads = new int[parties];
        }

        /// <summary>The managed thread id that ran each chunk in the last run.</summary>
        public int[] Threads { get; }

        public void Reset() => _arrived = 0;

        public void Execute(int chunk, int chunkCount)
        {
            Threads[chunk] = Environment.CurrentManagedThreadId;
            Interlocked.Increment(ref _arrived);
            var clock = Stopwatch.StartNew();
            var spinner = default(SpinWait);
            while (Volatile.Read(ref _arrived) < _parties)
            {
                if (clock.Elapsed > TimeSpan.FromSeconds(10))
                {
                    throw new TimeoutException($"chunk {chunk}: only {Volatile.Read(ref _arrived)} of {_parties} chunks ever ran at once");
                }

                spinner.SpinOnce();
            }
        }
    }

    private sealed class FailingWork : IParallelWork
    {
        private readonly int[] _failing;

        public FailingWork(int chunks, int[] failing)
        {
            Done = new int[chunks];
            _failing = failing;
        }

        public int[] Done { get; }

        public void Execute(int chunk, int chunkCount)
        {
            if (Array.IndexOf(_failing, chunk) >= 0)
            {
                throw new InvalidOperationException($"chunk {chunk}");
            }

            Thread.SpinWait(2000); // long enough that other chunks are still running when a failure is caught
            Interlocked.Exchange(ref Done[chunk], 1);
        }
    }

    private sealed class RecordingWork : IParallelWork
    {
        private int _calls;

        public RecordingWork(int chunks)
        {
            Order = new int[chunks];
            Threads = new int[chunks];
        }

        public int[] Order { get; }

        public int[] Threads { get; }

        public int Calls => _calls;

        public void Execute(int chunk, int chunkCount)
        {
            var call = Interlocked.Increment(ref _calls) - 1;
            Order[call] = chunk;
            Threads[chunk] = Environment.CurrentManagedThreadId;
        }
    }

    private sealed class CallbackWork : IParallelWork
    {
        private readonly Action<int> _callback;

        public CallbackWork(Action<int> callback)
        {
            _callback = callback;
        }

        public void Execute(int chunk, int chunkCount) => _callback(chunk);
    }

    private sealed class Flag
    {
        public int Value;
        public int FalseReads;
    }

    /// <summary>True once the flag is set, or after its given number of false reads.</summary>
    private readonly struct FlagSet : HandOffWaiter.ICondition
    {
        private readonly Flag _flag;

        public FlagSet(Flag flag)
        {
            _flag = flag;
        }

        public bool IsMet()
        {
            if (_flag.FalseReads > 0)
            {
                _flag.FalseReads--;
                return false;
            }

            return Volatile.Read(ref _flag.Value) != 0;
        }
    }
}
