using System;
using System.Collections.Generic;
using System.Diagnostics;
using System.Globalization;
using System.IO;
using System.Linq;
using BenchmarkDotNet.Reports;
using BenchmarkDotNet.Running;
using ParticlePhysics.Benchmarks.Stability;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The benchmark program. Without a mode it is BenchmarkDotNet's switcher (pass <c>--filter</c>, <c>--job</c>, ...);
/// its modes:
/// <list type="bullet">
/// <item><c>verify</c>: checks that the student baseline, Math.NET and the library give the same cloth, and that a
/// library step allocates nothing; exits 1 if not.</item>
/// <item><c>stability [--n 64] [--integrators a,b] [--write] [--verbose]</c>: the largest stable dt of each
/// integrator (<c>--dt X</c>: one trial at X instead of the search).</item>
/// <item><c>profile [--n 128] [--seconds 20] [--integrator xpbd|implicit-euler [--steps N] [--runner 2] [--tolerance 1e-3] [--preconditioner block-jacobi] [--per-frame]]</c>:
/// RK4 cloth steps (or xpbd or implicit-Euler frames) in a loop, for <c>perf record</c> or callgrind
/// (with <c>--runner</c>, <see cref="RunnerChoice"/>'s options choose the runner; <c>--per-frame</c> prints the
/// implicit solve's iterations of each frame of the first simulated second).</item>
/// <item><c>xpbd [--sizes 32,64,128,256] [--rounds 7] [--cores [--spin-us N]]</c>: a short
/// side-by-side timing of the C xpbd and the library in one process, alternating (or, with <c>--cores</c>, one core
/// against two), after a bit-for-bit check (<see cref="XpbdComparison"/>); <c>--lean</c>: the lean C
/// (<c>cloth_xpbd_lean.c</c>, no damping) against the library with damping 0 and with 0.05.</item>
/// <item><c>mesh-cloth --c | --scaling | --implicit | --cores</c>: a mesh cloth with membrane and bending: its
/// projections against their C reference, the cost per triangle from 1,000 to 100,000 triangles, implicit Euler
/// against the spring cloth, two cores against one (<see cref="MeshClothComparison"/>).</item>
/// <item><c>bodies --c [--bodies 100] [--side 4] [--passes 200]</c>: the rigid bodies' shape matching against its
/// plain C reference, after a bit-for-bit check (<see cref="BodiesComparison"/>).</item>
/// <item><c>cloth-world --aerodynamics [--n 64]</c>: what the air's drag and lift cost against the same mesh cloth
/// without them (<see cref="ClothWorldCosts"/>).</item>
/// <item><c>runner [--parallelism 2] [--rounds 5] [--ms 150] [--spin-us N] [--engine xpbd|implicit-euler [--n 64] [--tolerance 1e-3]]</c>: the cost
/// of a hand-off alone (or in the engine), one core against the runner that never spins and the runner as shipped, alternating
/// (<see cref="RunnerHandOffs"/>).</item>
/// <item><c>quality [--n 64]</c>: each solver's cloth after 5 s against RK4 at a small dt: lowest point, stretch of
/// the structural springs (<see cref="ClothQuality"/>; deterministic, no timing).</item>
/// <item><c>costs [batches]</c>: the cost of a step per step, per particle and per spring for each integrator, the
/// constants of the demo's run-cost estimate (<see cref="StepCosts"/>).</item>
/// <item><c>contacts [--sizes 1000,10000,100000] [--resolves 5] [--state DIR]</c>: the contact stage on settled piles,
/// outside BenchmarkDotNet: what each pile holds, a checksum of the result, the fastest resolve; for callgrind
/// (<see cref="ContactCosts"/>).</item>
/// <item><c>colliders [--levels 3,4,5,6,7,8] [--steps 120] [--rays 100000]</c>: the contact stage of a 64 x 64 cloth
/// draped on triangle meshes of 1,280 to 1,310,720 triangles, and a raycast against each (<see cref="ColliderCosts"/>).</item>
/// <item><c>obj [--vertices 1000000] [--rounds 7]</c>: the OBJ reader's throughput in MB/s on a generated mesh
/// (<see cref="ObjThroughput"/>).</item>
/// <item><c>--quick</c> (before BenchmarkDotNet's arguments): small cloths, for CI.</item>
/// </list>
/// After a BenchmarkDotNet run it exits 1 if any benchmark failed or has no result (NA).
/// </summary>
internal static class Program
{
    private static int Main(string[] args)
    {
        if (args.Length > 0 && args[0] == "obj")
        {
            return ObjThroughput.Run(args[1..]);
        }

        if (args.Length > 0 && args[0] == "verify")
        {
            return Verification.Run();
        }

        if (args.Length > 0 && args[0] == "stability")
        {
            return RunStability(args[1..]);
        }

        if (args.Length > 0 && args[0] == "profile")
        {
            return RunProfile(args[1..]);
        }

        if (args.Length > 0 && args[0] == "xpbd")
        {
            return XpbdComparison.Run(args[1..]);
        }

        if (args.Length > 0 && args[0] == "sleep")
        {
            return SleepingPile.Run(args[1..]);
        }

        if (args.Length > 0 && args[0] == "bodies")
        {
            return BodiesComparison.Run(args[1..]);
        }

        if (args.Length > 0 && args[0] == "mesh-cloth")
        {
            return MeshClothComparison.Run(args[1..]);
        }

        if (args.Length > 0 && args[0] == "cloth-world")
        {
            return ClothWorldCosts.Run(args[1..]);
        }

        if (args.Length > 0 && args[0] == "runner")
        {
            return RunnerHandOffs.Run(args[1..]);
        }

        if (args.Length > 0 && args[0] == "quality")
        {
            return ClothQuality.Run(args[1..]);
        }

        if (args.Length > 0 && args[0] == "costs")
        {
            return StepCosts.Run(args[1..]);
        }

        if (args.Length > 0 && args[0] == "colliders")
        {
            return ColliderCosts.Run(args[1..]);
        }

        if (args.Length > 0 && args[0] == "contacts")
        {
            return ContactCosts.Run(args[1..]);
        }

        var quick = args.Length > 0 && args[0] == "--quick";
        if (quick)
        {
            Environment.SetEnvironmentVariable(BenchmarkSizes.QuickVariable, "1");
            args = args[1..];
        }

        var summaries = BenchmarkSwitcher.FromAssembly(typeof(Program).Assembly).Run(args).ToList();
        var status = CheckSummaries(summaries);
        if (quick)
        {
            // CI: a filter that silently matches nothing must not pass.
            foreach (var type in new[] { typeof(ClothStepBenchmarks), typeof(IntegratorBenchmarks), typeof(ComparisonBenchmarks), typeof(ImplicitEulerBenchmarks), typeof(ParallelBenchmarks), typeof(ContactBenchmarks), typeof(XpbdBenchmarks), typeof(XpbdParallelBenchmarks) })
            {
                if (!summaries.Any(s => s.BenchmarksCases.Any(c => c.Descriptor.Type == type)))
                {
                    Console.Error.WriteLine($"error: quick mode did not run {type.Name}");
                    status = 1;
                }
            }
        }

        return status;
    }

    /// <summary>0 when every benchmark of every summary ran and has a result; 1 (with the reasons) otherwise.</summary>
    private static int CheckSummaries(IReadOnlyList<Summary> summaries)
    {
        var failures = new List<string>();
        foreach (var summary in summaries)
        {
            if (summary.HasCriticalValidationErrors)
            {
                failures.Add($"{summary.Title}: critical validation errors");
            }

            foreach (var benchmarkCase in summary.BenchmarksCases)
            {
                var report = summary[benchmarkCase];
                if (report is null || !report.Success || report.ResultStatistics is null)
                {
                    failures.Add($"{benchmarkCase.DisplayInfo}: no result (NA)");
                }
            }
        }

        foreach (var failure in failures)
        {
            Console.Error.WriteLine($"error: {failure}");
        }

        return failures.Count == 0 ? 0 : 1;
    }

    private static int RunStability(string[] args)
    {
        var n = int.Parse(Option(args, "--n") ?? BenchmarkSizes.IntegratorCloth.ToString(CultureInfo.InvariantCulture), CultureInfo.InvariantCulture);
        var names = Option(args, "--integrators")?.Split(',') ?? IntegratorCatalog.Names.ToArray();
        var write = args.Contains("--write");
        if (Option(args, "--dt") is { } single)
        {
            var dt = double.Parse(single, CultureInfo.InvariantCulture);
            foreach (var name in names)
            {
                var trial = StabilitySearch.Run(name, n, dt);
                Console.WriteLine(string.Create(
                    CultureInfo.InvariantCulture,
                    $"{name} at dt = {dt:G6} on the {n} x {n} cloth for {StabilitySearch.SimulatedSeconds} s: {trial.Reason}, farthest from a pin {trial.FarthestFromPin:G4} m"));
            }

            return 0;
        }

        var verbose = args.Contains("--verbose");
        Console.WriteLine(string.Create(
            CultureInfo.InvariantCulture,
            $"Largest stable dt on the {n} x {n} cloth: {StabilitySearch.SimulatedSeconds} s from rest within the divergence limit and every particle within {StabilitySearch.SaneDistance} m of a pin; bisected to {StabilitySearch.RelativePrecision:P0}, searched up to {StabilitySearch.LargestTried} s."));
        Console.WriteLine();
        Console.WriteLine($"| integrator | largest stable dt [s] | steps per simulated s | farthest from a pin [m] | search [s] |");
        Console.WriteLine($"| --- | ---: | ---: | ---: | ---: |");
        var lines = new List<string> { StableTimeSteps.Header };
        foreach (var name in names)
        {
            if (StableTimeSteps.IsAdaptive(name))
            {
                Console.WriteLine($"| {name} | adaptive (tolerance 1e-8) | - | - | - |");
                continue;
            }

            var clock = Stopwatch.StartNew();
            Action<double, StabilitySearch.Trial>? log = verbose
                ? (dt, trial) => Console.Error.WriteLine(string.Create(CultureInfo.InvariantCulture, $"  {name} dt={dt:G6}: {trial.Reason}"))
                : null;
            var largest = StabilitySearch.LargestStableTimeStep(name, n, log);
            var check = largest > 0 ? StabilitySearch.Run(name, n, largest) : default;
            var capped = largest >= StabilitySearch.LargestTried ? ">= " : string.Empty;
            Console.WriteLine(string.Create(
                CultureInfo.InvariantCulture,
                $"| {name} | {capped}{largest:G4} | {Math.Ceiling(1 / largest)} | {check.FarthestFromPin:F3} | {clock.Elapsed.TotalSeconds:F1} |"));
            lines.Add(StableTimeSteps.Format(name, n, largest));
        }

        if (write)
        {
            var path = Path.Combine(RepositoryRoot(), "benchmarks", "ParticlePhysics.Benchmarks", StableTimeSteps.FileName);
            var kept = File.Exists(path)
                ? File.ReadAllLines(path).Where(l => l != StableTimeSteps.Header && !names.Any(name => l.StartsWith(
                    string.Create(CultureInfo.InvariantCulture, $"{name},{n},"), StringComparison.Ordinal)))
                : Enumerable.Empty<string>();
            File.WriteAllLines(path, lines.Take(1).Concat(kept).Concat(lines.Skip(1)).Where(l => l.Length > 0));
            Console.WriteLine();
            Console.WriteLine($"wrote {path}; rebuild to embed it.");
        }

        return 0;
    }

    private static int RunProfile(string[] args)
    {
        var n = int.Parse(Option(args, "--n") ?? "128", CultureInfo.InvariantCulture);
        var seconds = double.Parse(Option(args, "--seconds") ?? "20", CultureInfo.InvariantCulture);
        if (Option(args, "--integrator") is "xpbd")
        {
            return RunXpbdProfile(n, seconds, Option(args, "--steps"), Option(args, "--runner"), args);
        }

        if (Option(args, "--integrator") is "implicit-euler")
        {
            return RunImplicitProfile(n, seconds, Option(args, "--steps"), Option(args, "--runner"), Option(args, "--tolerance"), args);
        }

        var cloth = new ClothFixture(n);
        var rk4 = new RungeKutta4();
        var clock = Stopwatch.StartNew();
        long steps = 0;
        while (clock.Elapsed.TotalSeconds < seconds)
        {
            cloth.Reset();
            for (var s = 0; s < ClothFixture.StepsPerInvoke; s++)
            {
                cloth.System.Step(rk4, cloth.TimeStep);
            }

            steps += ClothFixture.StepsPerInvoke;
        }

        var perStep = clock.Elapsed.TotalSeconds / steps;
        Console.WriteLine(string.Create(
            CultureInfo.InvariantCulture,
            $"n = {n}: {steps} RK4 steps, {perStep * 1e6:F1} us per step, {perStep * 1e9 / (4.0 * cloth.SpringCount):F2} ns per spring evaluation"));
        return 0;
    }

    /// <summary>
    /// xpbd frames of 1/60 s (10 substeps) from rest, a reset every simulated second: for <c>--seconds</c> of wall time
    /// (for perf), or exactly <c>--steps</c> frames (for callgrind: two run lengths, the difference is the frames'
    /// instructions), then the checksum that <c>cloth_xpbd --run</c> prints after as many frames from rest.
    /// </summary>
    private static int RunXpbdProfile(int n, double seconds, string? steps, string? runnerThreads, string[] args)
    {
        var cloth = new XpbdCloth(n);
        var runner = runnerThreads is null ? null : RunnerChoice.Create(args, int.Parse(runnerThreads, CultureInfo.InvariantCulture));
        using var disposeRunner = runner as IDisposable;
        cloth.Runner = runner;
        var fixedSteps = steps is null ? -1L : long.Parse(steps, CultureInfo.InvariantCulture);
        var clock = Stopwatch.StartNew();
        long frames = 0;
        cloth.Reset();
        while (fixedSteps >= 0 ? frames < fixedSteps : clock.Elapsed.TotalSeconds < seconds)
        {
            if (frames > 0 && frames % XpbdCloth.StepsPerSecond == 0)
            {
                cloth.Reset();
            }

            cloth.Run(1);
            frames++;
        }

        var perSecond = clock.Elapsed.TotalSeconds / Math.Max(1, frames) * XpbdCloth.StepsPerSecond;
        Console.WriteLine(string.Create(
            CultureInfo.InvariantCulture,
            $"n = {n}: {frames} xpbd frames, {perSecond * 1e3:F2} ms per simulated second, {perSecond * 1e9 / cloth.ProjectionsPerSecond:F2} ns per projection, checksum {cloth.Checksum():R}"));
        return 0;
    }

    /// <summary>
    /// Implicit Euler frames of 1/60 s from rest, a reset (and a cold solver) every simulated second, as
    /// <c>ImplicitEulerBenchmarks.SimulatedSecond</c> runs them: for <c>--seconds</c> of wall time (for perf), or exactly
    /// <c>--steps</c> frames (for callgrind: two run lengths, the difference is the frames' instructions); prints the
    /// mean CG iterations per frame and a checksum of the state (the sum of its values), the same on any runner.
    /// </summary>
    private static int RunImplicitProfile(int n, double seconds, string? steps, string? runnerThreads, string? tolerance, string[] args)
    {
        const int framesPerSecond = 60;
        var cloth = new ClothFixture(n);
        var implicitEuler = new ImplicitEuler
        {
            Tolerance = double.Parse(tolerance ?? "1e-3", CultureInfo.InvariantCulture),
            Preconditioner = Option(args, "--preconditioner") == "block-jacobi" ? ImplicitPreconditioner.BlockJacobi : ImplicitPreconditioner.Multigrid,
        };
        var runner = runnerThreads is null ? null : RunnerChoice.Create(args, int.Parse(runnerThreads, CultureInfo.InvariantCulture));
        using var disposeRunner = runner as IDisposable;
        cloth.System.Runner = runner;
        var fixedSteps = steps is null ? -1L : long.Parse(steps, CultureInfo.InvariantCulture);
        var firstSecond = new int[framesPerSecond]; // each frame's iterations, for --per-frame
        var clock = Stopwatch.StartNew();
        long frames = 0, iterations = 0;
        while (fixedSteps >= 0 ? frames < fixedSteps : clock.Elapsed.TotalSeconds < seconds)
        {
            if (frames % framesPerSecond == 0)
            {
                cloth.Reset();
                implicitEuler.ReadState(new double[] { 0 });
            }

            cloth.System.Step(implicitEuler, 1.0 / framesPerSecond);
            iterations += implicitEuler.LastIterations;
            if (frames < framesPerSecond)
            {
                firstSecond[frames] = implicitEuler.LastIterations;
            }

            frames++;
        }

        var perSecond = clock.Elapsed.TotalSeconds / Math.Max(1, frames) * framesPerSecond;
        var checksum = 0.0;
        foreach (var value in cloth.System.State)
        {
            checksum += value;
        }

        if (Array.IndexOf(args, "--per-frame") >= 0)
        {
            Console.WriteLine("CG iterations of each frame of the first simulated second: " + string.Join(
                " ", firstSecond.Take((int)Math.Min(frames, framesPerSecond)).Select(i => i.ToString(CultureInfo.InvariantCulture))));
        }

        Console.WriteLine(string.Create(
            CultureInfo.InvariantCulture,
            $"n = {n}: {frames} implicit-euler frames ({implicitEuler.Preconditioner}) at tolerance {implicitEuler.Tolerance:R}, {perSecond * 1e3:F2} ms per simulated second, {(double)iterations / Math.Max(1, frames):F3} CG iterations per frame, checksum {checksum:R}"));
        return 0;
    }

    internal static string? Option(string[] args, string name)
    {
        var i = Array.IndexOf(args, name);
        return i >= 0 && i + 1 < args.Length ? args[i + 1] : null;
    }

    /// <summary>The repository's root: the first directory above <paramref name="start"/> (default: the current one) with ParticlePhysics.sln.</summary>
    internal static string RepositoryRoot(string? start = null)
    {
        foreach (var from in new[] { start, Directory.GetCurrentDirectory() })
        {
            for (var dir = from is null ? null : new DirectoryInfo(from); dir is not null; dir = dir.Parent)
            {
                if (File.Exists(Path.Combine(dir.FullName, "ParticlePhysics.sln")))
                {
                    return dir.FullName;
                }
            }
        }

        throw new InvalidOperationException("Run from inside the repository: ParticlePhysics.sln not found above the current directory.");
    }
}
