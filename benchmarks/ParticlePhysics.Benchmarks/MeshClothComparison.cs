using System;
using System.Globalization;
using System.Linq;
using ParticlePhysics.Cloth;
using ParticlePhysics.Integrators;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The mesh-cloth mode (issue 29): a mesh cloth of n x n vertices (the course's grid triangulated as
/// <see cref="ClothMesh"/> does, 2 (n - 1)^2 triangles) with a membrane and plate bending, timed outside BenchmarkDotNet
/// in alternating rounds, the fastest round of each side reported with the median of the per-round ratios:
/// <list type="bullet">
/// <item><c>--c [--n 64] [--passes 200]</c>: the membrane and bending projections (one pass each per substep) against
/// their plain C reference (<see cref="NativeMeshXpbd"/>), after a bit-for-bit check of one pass.</item>
/// <item><c>--scaling [--sizes 23,72,225]</c>: xpbd frames of the whole cloth: ns per triangle per substep
/// (1,000, 10,000 and 100,000 triangles).</item>
/// <item><c>--implicit [--n 64] [--tolerance 1e-3]</c>: implicit Euler at 60 Hz, the mesh cloth against the course's
/// spring cloth of the same n (<see cref="ClothFixture"/>), one simulated second from rest each.</item>
/// <item><c>--cores [--n 225] [--integrator xpbd|implicit-euler]</c>: one core against <see cref="RunnerChoice"/>'s
/// runner (two workers), after checking that both give the same bits.</item>
/// </list>
/// Every variant takes <c>--rounds R</c> (default 5).
/// </summary>
internal static class MeshClothComparison
{
    public static int Run(string[] args)
    {
        var rounds = Int(args, "--rounds", 5);
        if (args.Contains("--c"))
        {
            return CompareWithC(Int(args, "--n", 64), Int(args, "--passes", 200), rounds);
        }

        if (args.Contains("--scaling"))
        {
            var sizes = (Program.Option(args, "--sizes") ?? "23,72,225").Split(',').Select(s => int.Parse(s, CultureInfo.InvariantCulture)).ToArray();
            return Scaling(sizes, rounds);
        }

        if (args.Contains("--implicit"))
        {
            var tolerance = double.Parse(Program.Option(args, "--tolerance") ?? "1e-3", CultureInfo.InvariantCulture);
            return CompareImplicit(Int(args, "--n", 64), tolerance, rounds);
        }

        if (args.Contains("--cores"))
        {
            return CompareCores(Int(args, "--n", 225), Program.Option(args, "--integrator") ?? "xpbd", rounds, args);
        }

        Console.Error.WriteLine("usage: mesh-cloth --c | --scaling | --implicit | --cores [options] (see MeshClothComparison)");
        return 2;
    }

    /// <summary>
    /// The n x n mesh cloth: 1 m square in y = 0, 1 kg, the corners of its first row pinned, Y = 100 N/m (about the
    /// course's springs of 50 N/m as a membrane), nu = 0.3, eta = 0.1 N s/m, D = 1e-4 N m, and the course's drag of
    /// 0.01 N s/m per particle at n = 64 spread over the n^2 particles (0.01 (64 / n)^2 each): xpbd takes drag
    /// explicitly, stable while h lambda / m &lt; 2, and a corner carries a sixth of an inner particle's mass.
    /// </summary>
    public static TriangleCloth Build(int n)
    {
        var r = 1.0 / (n - 1);
        var vertices = new double[3 * n * n];
        for (var i = 0; i < n * n; i++)
        {
            vertices[3 * i] = (i % n) * r;
            vertices[(3 * i) + 2] = (i / n) * r;
        }

        var builder = new MeshClothBuilder(new WeldedMesh(vertices, new ClothMesh(n, n).CreateTriangles()))
        {
            TotalMass = 1,
            Modulus = 100,
            Poisson = 0.3,
            MembraneDamping = 0.1,
            BendingRigidity = 1e-4,
            Drag = 0.01 * (64.0 / n) * (64.0 / n),
        };
        builder.Pin(0).Pin(n - 1);
        return builder.Build();
    }

    private static int CompareWithC(int n, int passes, int rounds)
    {
        var cloth = Build(n);
        var world = cloth.System;
        var particles = world.Count;
        using var c = new NativeMeshXpbd(particles, cloth.Membrane!, cloth.Bending!);
        var h = XpbdCloth.FrameTime / XpbdCloth.Substeps;
        c.Prepare(h);

        // A bent, stretched start, so that every projection moves its particles: x0 the flat cloth, x a wave over it.
        var x0 = world.State.Slice(0, 3 * particles).ToArray();
        var start = (double[])x0.Clone();
        for (var i = 0; i < particles; i++)
        {
            start[(3 * i) + 1] = 0.02 * Math.Sin(9 * x0[3 * i]) * Math.Cos(7 * x0[(3 * i) + 2]);
            start[3 * i] *= 1.01;
        }

        var v = new double[3 * particles];
        var w = world.InverseMasses.ToArray();
        var masses = world.Masses.ToArray();
        var xLibrary = (double[])start.Clone();
        var xC = (double[])start.Clone();
        void Library(int which, int count)
        {
            for (var p = 0; p < count; p++)
            {
                var context = new ConstraintContext(0, h, x0, v, xLibrary, v, masses, w);
                if ((which & 1) != 0)
                {
                    cloth.MembraneProjection!.Project(context);
                }

                if ((which & 2) != 0)
                {
                    cloth.BendingProjection!.Project(context);
                }
            }
        }

        Library(3, 1);
        c.Project(xC, x0, w, 1, 3);
        var same = xLibrary.AsSpan().SequenceEqual(xC);
        Console.WriteLine(string.Create(CultureInfo.InvariantCulture,
            $"n = {n}: {cloth.Mesh.TriangleCount} triangles, {((IBendingElements)cloth.Bending!).ElementCount} bending elements, {(same ? "same bits after one pass" : "DIFFERENT positions after one pass")}; {passes} passes per round, {rounds} rounds"));
        foreach (var (which, name, count) in new[] { (1, "membrane", cloth.Mesh.TriangleCount), (2, "bending", ((IBendingElements)cloth.Bending!).ElementCount), (3, "both", cloth.Mesh.TriangleCount) })
        {
            var (a, b) = Alternate(
                () =>
                {
                    start.CopyTo(xC, 0);
                    c.Project(xC, x0, w, passes, which);
                },
                () =>
                {
                    start.CopyTo(xLibrary, 0);
                    Library(which, passes);
                },
                rounds);
            var perElement = 1e6 / ((double)passes * count);
            Console.WriteLine(string.Create(CultureInfo.InvariantCulture,
                $"  {name,-8}: C {a.Min() * perElement:F2} ns, library {b.Min() * perElement:F2} ns per {(which == 3 ? "triangle (both)" : which == 1 ? "triangle" : "element")}; library / C {b.Min() / a.Min():F3}, median {Rounds.MedianRatio(b, a):F3}"));
        }

        return same ? 0 : 1;
    }

    private static int Scaling(int[] sizes, int rounds)
    {
        var cloths = sizes.Select(Build).ToArray();
        var initial = cloths.Select(c => c.System.State.ToArray()).ToArray();
        var xpbd = new Xpbd(XpbdCloth.Substeps);

        // About 2e6 triangle-frames per round for each size: 1000 frames of 1,000 triangles, 20 of 100,000.
        var frames = cloths.Select(c => Math.Max(1, (int)(2e6 / c.Mesh.TriangleCount))).ToArray();
        var times = cloths.Select(_ => new double[rounds]).ToArray();
        for (var r = -1; r < rounds; r++)
        {
            for (var k = 0; k < cloths.Length; k++)
            {
                var world = cloths[k].System;
                var (wall, _) = Rounds.Time(() =>
                {
                    world.SetState(initial[k]);
                    world.Time = 0;
                    for (var f = 0; f < frames[k]; f++)
                    {
                        world.Step(xpbd, XpbdCloth.FrameTime);
                    }
                });
                if (r >= 0)
                {
                    times[k][r] = wall;
                }
            }
        }

        Console.WriteLine($"xpbd, {XpbdCloth.Substeps} substeps per 1/60 s frame, membrane + bending, one core; {rounds} alternating rounds, fastest");
        var perTriangle = new double[cloths.Length];
        for (var k = 0; k < cloths.Length; k++)
        {
            var triangles = cloths[k].Mesh.TriangleCount;
            perTriangle[k] = times[k].Min() * 1e6 / ((double)frames[k] * XpbdCloth.Substeps * triangles);
            Console.WriteLine(string.Create(CultureInfo.InvariantCulture,
                $"  n = {sizes[k],3}: {triangles,6} triangles, {frames[k]} frames: {perTriangle[k]:F2} ns per triangle per substep (median round {Rounds.Median(times[k]) * 1e6 / ((double)frames[k] * XpbdCloth.Substeps * triangles):F2})"));
        }

        Console.WriteLine(string.Create(CultureInfo.InvariantCulture, $"  largest / smallest cost per triangle: {perTriangle.Max() / perTriangle.Min():F3}"));
        return 0;
    }

    private static int CompareImplicit(int n, double tolerance, int rounds)
    {
        var mesh = Build(n);
        var meshInitial = mesh.System.State.ToArray();
        var springs = new ClothFixture(n);
        var meshSolver = new ImplicitEuler { Tolerance = tolerance };
        var springSolver = new ImplicitEuler { Tolerance = tolerance };
        long meshIterations = 0, springIterations = 0;
        void Mesh()
        {
            mesh.System.SetState(meshInitial);
            mesh.System.Time = 0;
            for (var f = 0; f < XpbdCloth.StepsPerSecond; f++)
            {
                mesh.System.Step(meshSolver, XpbdCloth.FrameTime);
                meshIterations += meshSolver.LastIterations;
            }
        }

        void Springs()
        {
            springs.Reset();
            for (var f = 0; f < XpbdCloth.StepsPerSecond; f++)
            {
                springs.System.Step(springSolver, XpbdCloth.FrameTime);
                springIterations += springSolver.LastIterations;
            }
        }

        var (a, b) = Alternate(Springs, Mesh, rounds);
        var frames = (double)XpbdCloth.StepsPerSecond * (rounds + 2);
        Console.WriteLine(string.Create(CultureInfo.InvariantCulture,
            $"implicit Euler at 1/60 s, tolerance {tolerance:R}, n = {n}, one simulated second from rest, {rounds} alternating rounds: spring cloth ({springs.SpringCount} springs) {a.Min():F1} ms, {springIterations / frames:F1} CG iterations per frame; mesh cloth ({mesh.Mesh.TriangleCount} triangles, {((IBendingElements)mesh.Bending!).ElementCount} bending elements) {b.Min():F1} ms, {meshIterations / frames:F1} per frame; mesh / springs {b.Min() / a.Min():F3}, median {Rounds.MedianRatio(b, a):F3}"));
        return 0;
    }

    private static int CompareCores(int n, string integrator, int rounds, string[] args)
    {
        var cloth = Build(n);
        var initial = cloth.System.State.ToArray();
        var runner = RunnerChoice.Create(args, 2);
        using var disposeRunner = runner as IDisposable;
        var stepper = IntegratorCatalog.Create(integrator);
        var frames = integrator == "xpbd" ? 10 : 5;
        void Run(IParallelRunner? on)
        {
            cloth.System.Runner = on;
            cloth.System.SetState(initial);
            cloth.System.Time = 0;
            for (var f = 0; f < frames; f++)
            {
                cloth.System.Step(stepper, XpbdCloth.FrameTime);
            }
        }

        // Fresh integrators for the check, so that no warm start carries over between the two runs.
        stepper = IntegratorCatalog.Create(integrator);
        Run(null);
        var one = cloth.System.State.ToArray();
        stepper = IntegratorCatalog.Create(integrator);
        Run(runner);
        var same = cloth.System.State.SequenceEqual(one);
        var (a, b) = Alternate(() => Run(null), () => Run(runner), rounds);
        Console.WriteLine(string.Create(CultureInfo.InvariantCulture,
            $"{integrator}, n = {n} ({cloth.Mesh.TriangleCount} triangles, membrane + bending), {frames} frames of 1/60 s per round, {rounds} alternating rounds, {(same ? "same bits on one and two cores" : "DIFFERENT states on one and two cores")}: one core {a.Min():F1} ms, {RunnerChoice.Describe(args, 2)} {b.Min():F1} ms; speedup {a.Min() / b.Min():F3}, median {Rounds.MedianRatio(a, b):F3}"));
        return same ? 0 : 1;
    }

    /// <summary>One warm-up run of each, then <paramref name="rounds"/> rounds of first then second: wall times [ms].</summary>
    internal static (double[] First, double[] Second) Alternate(Action first, Action second, int rounds)
    {
        first();
        second();
        var a = new double[rounds];
        var b = new double[rounds];
        for (var r = 0; r < rounds; r++)
        {
            a[r] = Rounds.Time(first).Wall;
            b[r] = Rounds.Time(second).Wall;
        }

        return (a, b);
    }

    private static int Int(string[] args, string name, int fallback) =>
        int.Parse(Program.Option(args, name) ?? fallback.ToString(CultureInfo.InvariantCulture), CultureInfo.InvariantCulture);
}
