using System;
using System.Diagnostics;
using System.Globalization;
using System.IO;
using System.Linq;
using System.Threading;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The runner mode (issue 13): the cost of a hand-off alone, without the engine. The calling thread does a little
/// serial work, then a run of chunks of calibrated busy work, over and over, as the engine's passes do (xpbd: a
/// colour of a few microseconds per core, back to back; implicit Euler: passes of tens of microseconds between
/// serial pieces). The same loop on one core (the chunks in turn on the calling thread, no runner), with
/// <see cref="WorkerThreadRunner"/> that never spins (spin limit 0) and with <see cref="WorkerThreadRunner"/> as
/// shipped, in alternating rounds so that all see the same load.
/// Printed per case: wall time per run (fastest round, median of rounds), the process's CPU time per run, and the
/// median of the per-round ratios against one core.
/// <c>--engine xpbd|implicit-euler [--n 64] [--tolerance 1e-3]</c>: the same three on the engine instead, one simulated
/// second from rest per round (xpbd: 60 frames of 10 substeps; implicit Euler: 60 frames at the tolerance, 1e-3 by
/// default, from a cold solver, with its conjugate-gradient iterations per frame), each runner's state checked
/// bit-identical to one core's. <c>--spin-us N</c>: the adaptive runner with a spin limit of N
/// microseconds instead of the default.
/// </summary>
internal static class RunnerHandOffs
{
    /// <summary>The spin limit of the adaptive runner: the library's default, or <c>--spin-us N</c>.</summary>
    private static TimeSpan _spinLimit = WorkerThreadRunner.DefaultSpinLimit;

    public static int Run(string[] args)
    {
        var parallelism = int.Parse(Program.Option(args, "--parallelism") ?? "2", CultureInfo.InvariantCulture);
        var rounds = int.Parse(Program.Option(args, "--rounds") ?? "5", CultureInfo.InvariantCulture);
        if (Program.Option(args, "--spin-us") is { } spin)
        {
            _spinLimit = TimeSpan.FromTicks((long)Math.Round(double.Parse(spin, CultureInfo.InvariantCulture) * 10));
        }

        if (Program.Option(args, "--engine") is { } engine)
        {
            var n = int.Parse(Program.Option(args, "--n") ?? "64", CultureInfo.InvariantCulture);
            var tolerance = double.Parse(Program.Option(args, "--tolerance") ?? "1e-3", CultureInfo.InvariantCulture);
            return RunEngine(engine, n, tolerance, parallelism, rounds);
        }

        var milliseconds = double.Parse(Program.Option(args, "--ms") ?? "150", CultureInfo.InvariantCulture);
        var perMicrosecond = Calibrate();
        Console.WriteLine(string.Create(
            CultureInfo.InvariantCulture,
            $"runner hand-offs: {parallelism} threads, {rounds} rounds of about {milliseconds} ms per runner and case, alternating; load average {LoadAverage()}, {Environment.ProcessorCount} cores"));
        Console.WriteLine(string.Create(CultureInfo.InvariantCulture, $"busy work calibrated at {perMicrosecond:F1} iterations per us (fastest of 5)"));
        Console.WriteLine("per run: serial work on the calling thread, then the chunks; us per run: fastest round (median); CPU: the process's CPU time per run (median);");
        Console.WriteLine("x one core: median of the per-round ratios of wall time (above 1: faster)");

        // A chunk time of -1: the rendezvous, one chunk per thread, each waiting until all have started, so that every
        // thread must take part: the pure cost of handing a run to the workers and back (no one-core figure).
        var cases = new (double ChunkMicroseconds, int Chunks, double SerialMicroseconds)[]
        {
            (-1, parallelism, 0),
            (0, parallelism, 0),
            (2.5, 2 * parallelism, 1),
            (5, 2 * parallelism, 5),
            (10, 2 * parallelism, 10),
            (25, 2 * parallelism, 20),
            (50, parallelism, 20),
        };
        foreach (var (chunkMicroseconds, chunks, serialMicroseconds) in cases)
        {
            RunCase(parallelism, rounds, milliseconds, perMicrosecond, chunkMicroseconds, chunks, serialMicroseconds);
        }

        return 0;
    }

    private static void RunCase(int parallelism, int rounds, double milliseconds, double perMicrosecond, double chunkMicroseconds, int chunks, double serialMicroseconds)
    {
        var rendezvous = chunkMicroseconds < 0;
        var work = new BusyWork(rendezvous ? 0 : (long)Math.Round(chunkMicroseconds * perMicrosecond), rendezvous);
        var serial = (long)Math.Round(serialMicroseconds * perMicrosecond);
        using var contenders = new Contenders(parallelism);
        var runners = contenders.Rows;
        var oneCoreMicroseconds = serialMicroseconds + (chunks * Math.Max(0, chunkMicroseconds));
        var runs = (int)Math.Max(200, milliseconds * 1000 / Math.Max(2, oneCoreMicroseconds));
        var wall = runners.Select(_ => new double[rounds]).ToArray();
        var cpu = runners.Select(_ => new double[rounds]).ToArray();
        for (var k = 0; k < runners.Length; k++)
        {
            Measure(runners[k].Runner, work, chunks, serial, Math.Max(1, runs / 10)); // warm-up
        }

        for (var r = 0; r < rounds; r++)
        {
            for (var k = 0; k < runners.Length; k++)
            {
                (wall[k][r], cpu[k][r]) = Measure(runners[k].Runner, work, chunks, serial, runs);
            }
        }

        Console.WriteLine(rendezvous
            ? $"{chunks} chunks that wait for each other (every thread takes one), {runs} runs per round:"
            : string.Create(
                CultureInfo.InvariantCulture,
                $"{chunks} chunks of {chunkMicroseconds} us after {serialMicroseconds} us of serial work ({oneCoreMicroseconds} us on one core), {runs} runs per round:"));
        for (var k = 0; k < runners.Length; k++)
        {
            Console.WriteLine(string.Create(
                CultureInfo.InvariantCulture,
                $"  {runners[k].Name,-22} {wall[k].Min(),8:F2} ({Rounds.Median(wall[k]),8:F2}) us per run, CPU {Rounds.Median(cpu[k]),8:F2} us; x one core {Rounds.MedianRatio(wall[0], wall[k]),6:F3}"));
        }
    }

    private static int RunEngine(string engine, int n, double tolerance, int parallelism, int rounds)
    {
        Action<IParallelRunner?> simulateSecond;
        Func<double[]> state;
        var label = engine;
        var iterations = 0;
        if (engine == "xpbd")
        {
            var cloth = new XpbdCloth(n);
            simulateSecond = runner =>
            {
                cloth.Runner = runner;
                cloth.SimulateSecond();
            };
            state = () => cloth.System.State.ToArray();
        }
        else if (engine == "implicit-euler")
        {
            var cloth = new ClothFixture(n);
            var implicitEuler = new Integrators.ImplicitEuler { Tolerance = tolerance };
            simulateSecond = runner =>
            {
                cloth.System.Runner = runner;
                cloth.Reset();
                implicitEuler.ReadState(new double[] { 0 }); // a cold solver, as the profile mode and the benchmark
                iterations = 0;
                for (var frame = 0; frame < 60; frame++)
                {
                    cloth.System.Step(implicitEuler, 1.0 / 60);
                    iterations += implicitEuler.LastIterations;
                }
            };
            state = () => cloth.System.State.ToArray();
        }
        else
        {
            Console.Error.WriteLine($"error: --engine {engine}: expected xpbd or implicit-euler");
            return 1;
        }

        using var contenders = new Contenders(parallelism);
        var runners = contenders.Rows;
        simulateSecond(null);
        var expected = state();
        if (engine == "implicit-euler")
        {
            label = string.Create(CultureInfo.InvariantCulture, $"implicit-euler (tolerance {tolerance:0.##e+0}, {iterations / 60.0:F2} CG iterations per frame)");
        }

        Console.WriteLine(string.Create(
            CultureInfo.InvariantCulture,
            $"{label}, {n} x {n} cloth, one simulated second from rest per round: one core and {parallelism} threads, {rounds} rounds alternating; load average {LoadAverage()}, {Environment.ProcessorCount} cores"));
        var same = true;
        foreach (var (_, runner) in runners)
        {
            simulateSecond(runner); // warm-up, and the bits
            same &= state().AsSpan().SequenceEqual(expected);
        }

        var wall = runners.Select(_ => new double[rounds]).ToArray();
        var cpu = runners.Select(_ => new double[rounds]).ToArray();
        var adaptive = contenders.Adaptive;
        long sleeps = adaptive.Sleeps, spins = adaptive.SpinningWaits;
        var counting = new CountingRunner(adaptive);
        for (var r = 0; r < rounds; r++)
        {
            for (var k = 0; k < runners.Length; k++)
            {
                var runner = ReferenceEquals(runners[k].Runner, adaptive) ? counting : runners[k].Runner;
                (wall[k][r], cpu[k][r]) = Rounds.Time(() => simulateSecond(runner));
            }
        }

        var handOffs = counting.Runs;
        sleeps = adaptive.Sleeps - sleeps;
        spins = adaptive.SpinningWaits - spins;

        Console.WriteLine(same ? "same bits with every runner as on one core" : "error: a runner gave DIFFERENT bits from one core");
        Console.WriteLine("ms per simulated second: fastest round (median); CPU: the process's CPU time (median); x one core: median of the per-round ratios of wall time");
        for (var k = 0; k < runners.Length; k++)
        {
            Console.WriteLine(string.Create(
                CultureInfo.InvariantCulture,
                $"  {runners[k].Name,-22} {wall[k].Min(),9:F2} ({Rounds.Median(wall[k]),9:F2}) ms, CPU {Rounds.Median(cpu[k]),9:F2} ms; x one core {Rounds.MedianRatio(wall[0], wall[k]),6:F3}"));
        }

        Console.WriteLine(string.Create(
            CultureInfo.InvariantCulture,
            $"  the adaptive runner over its rounds: {handOffs} hand-offs; its threads slept {sleeps} times ({(double)sleeps / handOffs:F3} per hand-off) and spun first {spins} times"));
        return same ? 0 : 1;
    }

    /// <summary>
    /// The runners every case compares, in the order of its rows: one core (no runner), the shipped runner that never
    /// spins, and the shipped runner at the spin limit of <c>--spin-us</c> (its default otherwise).
    /// </summary>
    private sealed class Contenders : IDisposable
    {
        private readonly WorkerThreadRunner _blocking;

        public Contenders(int parallelism)
        {
            _blocking = new WorkerThreadRunner(parallelism, TimeSpan.Zero);
            Adaptive = new WorkerThreadRunner(parallelism, _spinLimit);
            Rows = new (string Name, IParallelRunner? Runner)[]
            {
                ("one core", null),
                ("spin limit 0", _blocking),
                (string.Create(CultureInfo.InvariantCulture, $"adaptive, {Adaptive.SpinLimit.TotalMilliseconds * 1000} us"), Adaptive),
            };
        }

        public WorkerThreadRunner Adaptive { get; }

        public (string Name, IParallelRunner? Runner)[] Rows { get; }

        public void Dispose()
        {
            _blocking.Dispose();
            Adaptive.Dispose();
        }
    }

    /// <summary>A runner that counts the runs it passes on (the wrapper costs one interface call per run).</summary>
    private sealed class CountingRunner : IParallelRunner
    {
        private readonly IParallelRunner _inner;

        public CountingRunner(IParallelRunner inner) => _inner = inner;

        public long Runs { get; private set; }

        public int MaxParallelism => _inner.MaxParallelism;

        public void Run(IParallelWork work, int chunkCount)
        {
            Runs++;
            _inner.Run(work, chunkCount);
        }
    }

    /// <summary>Wall and process CPU time per run [us] of <paramref name="runs"/> runs.</summary>
    private static (double Wall, double Cpu) Measure(IParallelRunner? runner, BusyWork work, int chunks, long serial, int runs)
    {
        if (runner is null && work.Rendezvous)
        {
            return (double.NaN, double.NaN); // one thread cannot meet itself
        }

        using var process = Process.GetCurrentProcess();
        var cpu = process.TotalProcessorTime;
        var clock = Stopwatch.StartNew();
        for (var i = 0; i < runs; i++)
        {
            BusyWork.Sink = BusyWork.Burn(serial, i);
            if (runner is null)
            {
                for (var c = 0; c < chunks; c++)
                {
                    work.Execute(c, chunks);
                }
            }
            else
            {
                runner.Run(work, chunks);
            }
        }

        var wall = clock.Elapsed.TotalMilliseconds * 1000 / runs;
        process.Refresh();
        return (wall, (process.TotalProcessorTime - cpu).TotalMilliseconds * 1000 / runs);
    }

    /// <summary>Iterations of <see cref="BusyWork.Burn"/> per microsecond: the fastest of 5 tries of about 5 ms.</summary>
    private static double Calibrate()
    {
        const long iterations = 2_000_000;
        var best = 0.0;
        BusyWork.Burn(iterations / 10, 1);
        for (var t = 0; t < 5; t++)
        {
            var clock = Stopwatch.StartNew();
            BusyWork.Burn(iterations, t);
            best = Math.Max(best, iterations / (clock.Elapsed.TotalMilliseconds * 1000));
        }

        return best;
    }

    private static string LoadAverage() =>
        File.Exists("/proc/loadavg") ? string.Join(' ', File.ReadAllText("/proc/loadavg").Split(' ').Take(3)) : "unknown";

    /// <summary>Chunks of a dependent chain of multiply-adds: a fixed time per chunk, no memory traffic.</summary>
    private sealed class BusyWork : IParallelWork
    {
        private readonly long _iterations;
        private readonly double[] _sink = new double[64 * 8];
        private long _arrived;

        /// <summary>Where the serial work's result goes, so that the compiler keeps the loop.</summary>
        public static double Sink { get; set; }

        public BusyWork(long iterations, bool rendezvous)
        {
            _iterations = iterations;
            Rendezvous = rendezvous;
        }

        /// <summary>Each chunk waits until every chunk of its run has started (instead of burning).</summary>
        public bool Rendezvous { get; }

        public static double Burn(long iterations, double seed)
        {
            var x = seed;
            for (var i = 0L; i < iterations; i++)
            {
                x = (x * 0.999999) + 1e-6;
            }

            return x;
        }

        public void Execute(int chunk, int chunkCount)
        {
            if (!Rendezvous)
            {
                _sink[(chunk & 63) * 8] = Burn(_iterations, chunk);
                return;
            }

            // The k-th arrival overall belongs to run (k - 1) / chunkCount: wait for that run's last arrival.
            var ticket = Interlocked.Increment(ref _arrived);
            var goal = (((ticket - 1) / chunkCount) + 1) * chunkCount;
            var spinner = default(SpinWait);
            while (Volatile.Read(ref _arrived) < goal)
            {
                spinner.SpinOnce(sleep1Threshold: -1);
            }
        }
    }
}
