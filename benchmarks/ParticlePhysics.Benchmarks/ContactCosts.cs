using System;
using System.Diagnostics;
using System.Globalization;
using System.IO;
using System.Linq;
using ParticlePhysics.Contacts;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The <c>contacts</c> mode: <see cref="ContactBenchmarks"/>' operation (one <see cref="ContactSet.Resolve"/> on a
/// settled pile of N particles) outside BenchmarkDotNet, for callgrind and for a description of the piles: candidate
/// pairs, impacts and particles near a wall per particle, a checksum of the corrected state (which changes if and only
/// if the stage's results change), and the fastest of the resolves' wall times.
/// </summary>
/// <remarks>
/// <c>--resolves K</c> runs the stage in batches of K resolves per 100,000 particles (100 K at 1,000 particles, K at
/// 100,000, at least one) on the same input, one batch per size in each of <c>--rounds R</c> rounds, the sizes in turn; the table
/// gives the fastest batch, in wall time and in the process's CPU time (which a loaded machine's preemption does not
/// count), per resolve. The difference of two runs of one size under callgrind (K = 3 and K = 1, divided by the
/// difference of resolves times N) is the stage's cost per particle per step with start-up, setup and compilation
/// cancelled: <c>contacts --sizes 1000 --resolves 0.01 --rounds 1 --no-warmup</c> resolves once, <c>--resolves 0.03</c>
/// three times.
/// <c>--state DIR</c> keeps each settled pile (100 RK4 steps of 1 ms) in DIR and reads it back on the next run, so
/// that a run under valgrind does not spend hours settling 100,000 particles (the state of the pile the stage sees is
/// then the same before and after a change of the stage); <c>--no-warmup</c> skips the second of
/// resolves on a small pile that otherwise comes first (for the timings; callgrind's difference cancels it anyway).
/// </remarks>
internal static class ContactCosts
{
    private const double Dt = 0.001;

    public static int Run(string[] args)
    {
        var sizes = (Program.Option(args, "--sizes") ?? "1000,10000,100000")
            .Split(',').Select(s => int.Parse(s, CultureInfo.InvariantCulture)).ToArray();
        var resolves = double.Parse(Program.Option(args, "--resolves") ?? "1", CultureInfo.InvariantCulture);
        var stateDirectory = Program.Option(args, "--state");
        if (!args.Contains("--no-warmup"))
        {
            Warm();
        }

        var rounds = int.Parse(Program.Option(args, "--rounds") ?? "5", CultureInfo.InvariantCulture);
        var piles = sizes.Select(n => new Pile(n, stateDirectory)).ToArray();
        for (var round = 0; round < rounds; round++)
        {
            // The sizes in turn, round after round, so that a loaded machine slows each of them alike.
            foreach (var pile in piles)
            {
                pile.Time(Math.Max(1, (int)Math.Ceiling(resolves * 100_000.0 / pile.World.Count)));
            }
        }

        Console.WriteLine("| particles | pairs per particle | impacts per particle | near a wall | checksum | resolves | fastest [ms] | per particle [us] | CPU per particle [us] |");
        Console.WriteLine("| ---: | ---: | ---: | ---: | --- | ---: | ---: | ---: | ---: |");
        foreach (var pile in piles)
        {
            var n = pile.World.Count;
            Console.WriteLine(string.Create(
                CultureInfo.InvariantCulture,
                $"| {n} | {(double)pile.Contacts.CandidatePairCount / n:F3} | {(double)pile.Contacts.ImpactCount / n:F4} | {pile.NearWall():P1} | {Checksum(pile.Work)} | {pile.Resolves} | {pile.Fastest * 1e3:F3} | {pile.Fastest * 1e6 / n:F3} | {pile.FastestCpu * 1e6 / n:F3} |"));
        }

        return 0;
    }

    /// <summary>A second of resolves on a small pile first, so that the timed ones run optimized code.</summary>
    private static void Warm()
    {
        var world = new ParticleBoxScenario { Count = 1000 }.Build();
        var contacts = world.Constraints.OfType<ContactSet>().Single();
        Settle(world, null);
        var start = world.State.ToArray();
        var work = GravityStepEnd(start, world.Count);
        var clock = Stopwatch.StartNew();
        while (clock.Elapsed.TotalSeconds < 1.0)
        {
            Resolve(world, contacts, start, (double[])work.Clone());
        }
    }

    /// <summary>100 RK4 steps of 1 ms from the scenario's start, or the state a previous run kept in the directory.</summary>
    private static void Settle(ParticleWorld world, string? directory)
    {
        var path = directory is null ? null : Path.Combine(directory, string.Create(CultureInfo.InvariantCulture, $"pile-{world.Count}.bin"));
        if (path is not null && File.Exists(path))
        {
            var bytes = File.ReadAllBytes(path);
            var state = new double[bytes.Length / sizeof(double)];
            Buffer.BlockCopy(bytes, 0, state, 0, bytes.Length);
            world.SetState(state);
            return;
        }

        var rk4 = new RungeKutta4();
        for (var s = 0; s < 100; s++)
        {
            world.Step(rk4, Dt);
        }

        if (path is not null)
        {
            var state = world.State.ToArray();
            var bytes = new byte[state.Length * sizeof(double)];
            Buffer.BlockCopy(state, 0, bytes, 0, bytes.Length);
            Directory.CreateDirectory(directory!);
            File.WriteAllBytes(path, bytes);
        }
    }

    /// <summary>The integrator's end of one more step under gravity alone, as in <see cref="ContactBenchmarks"/>.</summary>
    private static double[] GravityStepEnd(double[] start, int n)
    {
        var end = (double[])start.Clone();
        for (var i = 0; i < n; i++)
        {
            var y = (3 * i) + 1;
            end[y] += (start[(3 * n) + y] * Dt) - (0.5 * 9.81 * Dt * Dt);
            end[(3 * n) + y] -= 9.81 * Dt;
        }

        return end;
    }

    private static void Resolve(ParticleWorld world, ContactSet contacts, double[] start, double[] work)
    {
        var n = world.Count;
        var context = new ConstraintContext(
            0, Dt, start.AsSpan(0, 3 * n), start.AsSpan(3 * n), work.AsSpan(0, 3 * n), work.AsSpan(3 * n),
            world.Masses, world.InverseMasses, world.Radii);
        contacts.Resolve(in context);
    }

    /// <summary>FNV-1a over the bits of the values: equal checksums, (almost surely) equal states.</summary>
    private static string Checksum(double[] values)
    {
        var hash = 14695981039346656037UL;
        foreach (var value in values)
        {
            hash = (hash ^ (ulong)BitConverter.DoubleToInt64Bits(value)) * 1099511628211UL;
        }

        return hash.ToString("X16", CultureInfo.InvariantCulture);
    }

    /// <summary>A settled pile, the input of its stage, and the fastest resolve so far.</summary>
    private sealed class Pile
    {
        private readonly ParticleBoxScenario _scenario;
        private readonly double[] _start;
        private readonly double[] _end;

        public Pile(int n, string? stateDirectory)
        {
            _scenario = new ParticleBoxScenario { Count = n };
            World = _scenario.Build();
            Contacts = World.Constraints.OfType<ContactSet>().Single();
            Settle(World, stateDirectory);
            _start = World.State.ToArray();
            _end = GravityStepEnd(_start, n);
            Work = (double[])_end.Clone();
        }

        public ParticleWorld World { get; }

        public ContactSet Contacts { get; }

        public double[] Work { get; }

        /// <summary>The fastest batch's wall time per resolve, in seconds.</summary>
        public double Fastest { get; private set; } = double.PositiveInfinity;

        /// <summary>The fastest batch's CPU time per resolve, in seconds.</summary>
        public double FastestCpu { get; private set; } = double.PositiveInfinity;

        /// <summary>The resolves run so far.</summary>
        public int Resolves { get; private set; }

        public void Time(int resolves)
        {
            var process = Process.GetCurrentProcess();
            process.Refresh();
            var cpu = process.TotalProcessorTime;
            var clock = Stopwatch.StartNew();
            for (var k = 0; k < resolves; k++)
            {
                // The copy of the integrator's end is timed too, as in ContactBenchmarks (6 N doubles).
                _end.CopyTo(Work, 0);
                Resolve(World, Contacts, _start, Work);
            }

            var wall = clock.Elapsed.TotalSeconds;
            process.Refresh();
            Fastest = Math.Min(Fastest, wall / resolves);
            FastestCpu = Math.Min(FastestCpu, (process.TotalProcessorTime - cpu).TotalSeconds / resolves);
            Resolves += resolves;
        }

        /// <summary>The share of the particles within 1.25 r of a wall.</summary>
        public double NearWall()
        {
            var count = 0;
            var margin = 1.25 * _scenario.Radius;
            for (var i = 0; i < World.Count; i++)
            {
                var x = World.GetPosition(i);
                if (x.X < margin || x.Z < margin || x.X > _scenario.Width - margin || x.Z > _scenario.Width - margin)
                {
                    count++;
                }
            }

            return (double)count / World.Count;
        }
    }
}
