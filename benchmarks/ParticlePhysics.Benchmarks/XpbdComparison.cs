using System;
using System.Globalization;
using System.Linq;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The xpbd mode (issue 13): a short side-by-side timing for a machine that BenchmarkDotNet's default job would take
/// too long on, or that is shared. For each n, one process: the C reference (<see cref="NativeXpbd"/>) and the library
/// must give the same state to the last bit after one simulated second; then, after two warm-up seconds each, they
/// simulate one second from rest in turn, <c>--rounds</c> times, so that both see the same load. Printed: the
/// fastest round of each (wall time and process CPU time), the ratio of the fastest, and the median of the rounds'
/// ratios. <c>--cores</c>: the same for the library on one core against <see cref="WorkerThreadRunner"/>(2) (or the
/// runner that <see cref="RunnerChoice"/>'s options name), with the two cloths checked bit-identical; the speedup is of
/// wall times, and the CPU time (which adds the cores up) says what the second core cost: two cores' CPU time over one
/// core's is 1 for a perfect split, more for the hand-offs' waits.
/// </summary>
internal static class XpbdComparison
{
    public static int Run(string[] args)
    {
        var sizes = (Program.Option(args, "--sizes") ?? "32,64,128,256").Split(',').Select(s => int.Parse(s, CultureInfo.InvariantCulture)).ToArray();
        var rounds = int.Parse(Program.Option(args, "--rounds") ?? "7", CultureInfo.InvariantCulture);
        var cores = args.Contains("--cores");
        if (args.Contains("--lean"))
        {
            Console.WriteLine("xpbd, 10 substeps per 1/60 s frame, one simulated second from rest: the lean C (cloth_xpbd_lean.c, no damping) vs the library with damping 0, and the library with the course's damping 0.05, alternating");
            Console.WriteLine(string.Create(CultureInfo.InvariantCulture, $"{rounds} rounds; fastest round [ms]; ratio to the lean C of the fastest; median of the per-round ratios"));
            foreach (var n in sizes)
            {
                CompareWithLean(n, rounds);
            }

            return 0;
        }

        Console.WriteLine(cores
            ? $"xpbd, 10 substeps per 1/60 s frame, one simulated second from rest: library on one core vs {RunnerChoice.Describe(args, 2)}, alternating"
            : "xpbd, 10 substeps per 1/60 s frame, one simulated second from rest: C reference (gcc -O3) vs library on one core, alternating");
        Console.WriteLine(string.Create(CultureInfo.InvariantCulture, $"{rounds} rounds; fastest round [ms] (CPU time of the process in brackets); ratio of the fastest; median of the per-round ratios (of CPU times)"));
        var ok = true;
        foreach (var n in sizes)
        {
            ok &= cores ? CompareCores(n, rounds, args) : CompareWithC(n, rounds);
        }

        return ok ? 0 : 1;
    }

    private static bool CompareWithC(int n, int rounds)
    {
        using var c = new NativeXpbd(n);
        var library = new XpbdCloth(n);
        try
        {
            XpbdBenchmarks.SameCloth(c, library);
        }
        catch (InvalidOperationException exception)
        {
            Console.WriteLine($"error: {exception.Message}");
            return false;
        }

        void RunC()
        {
            c.Reset();
            c.Run(XpbdCloth.FrameTime, XpbdCloth.Substeps, XpbdCloth.StepsPerSecond);
        }

        var (a, b) = Alternate(RunC, library.SimulateSecond, rounds);
        Console.WriteLine(string.Create(
            CultureInfo.InvariantCulture,
            $"n = {n,3} ({library.SpringCount} springs, same bits): C {a.BestWall:F2} ({a.BestCpu:F2}) ms, library {b.BestWall:F2} ({b.BestCpu:F2}) ms; C# / C {b.BestWall / a.BestWall:F3} (CPU {b.BestCpu / a.BestCpu:F3}), median {Rounds.MedianRatio(b.Wall, a.Wall):F3} (CPU {Rounds.MedianRatio(b.Cpu, a.Cpu):F3}); library {b.BestWall * 1e6 / library.ProjectionsPerSecond:F2} ns, C {a.BestWall * 1e6 / library.ProjectionsPerSecond:F2} ns per projection"));
        return true;
    }

    /// <summary>
    /// The lean C (no damping, twelve structured batches, separate arrays) against the library with damping 0 and with
    /// the course's 0.05, three-way alternating. The lean C's order is not the library's: the checksums differ a little.
    /// </summary>
    private static void CompareWithLean(int n, int rounds)
    {
        using var lean = new NativeLeanXpbd(n);
        var undamped = new XpbdCloth(n, 0.0);
        var damped = new XpbdCloth(n);
        void RunLean()
        {
            lean.Reset();
            lean.Run(XpbdCloth.FrameTime, XpbdCloth.Substeps, XpbdCloth.StepsPerSecond);
        }

        var (l, u) = Alternate(RunLean, undamped.SimulateSecond, rounds);
        var (l2, d) = Alternate(RunLean, damped.SimulateSecond, rounds);
        var projections = undamped.ProjectionsPerSecond;
        Console.WriteLine(string.Create(
            CultureInfo.InvariantCulture,
            $"n = {n,3} ({lean.SpringCount} springs; checksums lean {lean.Checksum():G10}, library {undamped.Checksum():G10}): lean C {l.BestWall:F2} ms ({l.BestWall * 1e6 / projections:F2} ns per projection); library, damping 0: {u.BestWall:F2} ms ({u.BestWall * 1e6 / projections:F2} ns), {u.BestWall / l.BestWall:F3}x, median {Rounds.MedianRatio(u.Wall, l.Wall):F3}; library, damping 0.05: {d.BestWall:F2} ms ({d.BestWall * 1e6 / projections:F2} ns), {d.BestWall / l2.BestWall:F3}x, median {Rounds.MedianRatio(d.Wall, l2.Wall):F3}"));
    }

    private static bool CompareCores(int n, int rounds, string[] args)
    {
        var cloth = new XpbdCloth(n);
        var runner = RunnerChoice.Create(args, 2);
        using var disposeRunner = runner as IDisposable;
        cloth.SimulateSecond();
        var one = cloth.Checksum();
        var oneState = cloth.System.State.ToArray();
        cloth.Runner = runner;
        cloth.SimulateSecond();
        var same = cloth.System.State.SequenceEqual(oneState);
        void OneCore()
        {
            cloth.Runner = null;
            cloth.SimulateSecond();
        }

        void TwoCores()
        {
            cloth.Runner = runner;
            cloth.SimulateSecond();
        }

        var (a, b) = Alternate(OneCore, TwoCores, rounds);
        Console.WriteLine(string.Create(
            CultureInfo.InvariantCulture,
            $"n = {n,3} (checksum {one:R}, {(same ? "same bits on one and two cores" : "DIFFERENT states on one and two cores")}): one core {a.BestWall:F2} ({a.BestCpu:F2}) ms, two {b.BestWall:F2} ({b.BestCpu:F2}) ms; speedup {a.BestWall / b.BestWall:F3}, median {Rounds.MedianRatio(a.Wall, b.Wall):F3}; CPU two / one {b.BestCpu / a.BestCpu:F3}, median {Rounds.MedianRatio(b.Cpu, a.Cpu):F3}"));
        return same;
    }

    /// <summary>Two warm-up runs of each, then <paramref name="rounds"/> rounds of first then second.</summary>
    private static (Times First, Times Second) Alternate(Action first, Action second, int rounds)
    {
        for (var i = 0; i < 2; i++)
        {
            first();
            second();
        }

        var a = new Times(rounds);
        var b = new Times(rounds);
        for (var r = 0; r < rounds; r++)
        {
            a.Measure(r, first);
            b.Measure(r, second);
        }

        return (a, b);
    }

    private sealed class Times
    {
        public Times(int rounds)
        {
            Wall = new double[rounds];
            Cpu = new double[rounds];
        }

        /// <summary>Wall time of each round [ms].</summary>
        public double[] Wall { get; }

        /// <summary>CPU time of the process in each round [ms].</summary>
        public double[] Cpu { get; }

        public double BestWall => Wall.Min();

        public double BestCpu => Cpu.Min();

        public void Measure(int round, Action action) => (Wall[round], Cpu[round]) = Rounds.Time(action);
    }
}
