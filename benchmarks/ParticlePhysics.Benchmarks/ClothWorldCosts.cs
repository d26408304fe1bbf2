using System;
using System.Globalization;
using System.Linq;
using ParticlePhysics.Aerodynamics;
using ParticlePhysics.Cloth;
using ParticlePhysics.Contacts;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The cloth-world mode (issue 30): what the cloth's features cost against the same cloth without them, side by side
/// in one process in alternating rounds.
/// <list type="bullet">
/// <item><c>--aerodynamics [--n 64] [--frames 120] [--rounds 7]</c>: <see cref="MeshClothComparison.Build"/>'s n x n
/// mesh cloth at 60 Hz under xpbd (10 substeps) hanging in a 5 m/s wind with a gust (C_d 1.2, C_l 0.5), against the
/// same cloth without air; and the aerodynamics' own evaluations timed alone (one per substep), as a share of the
/// frame without air. Target: at most 10 %.</item>
/// <item><c>--self-collision [--n 64] [--frames 120] [--rounds 3]</c>: an n x n cloth (2.5 cm spacing, thickness 1 cm)
/// dropped from 10 cm above a sphere of radius 30 cm on the floor, draping and folding onto itself, at 60 Hz under xpbd
/// (10 substeps), with <see cref="ClothSelfCollision"/> against the same drop without it (floor and sphere in both).
/// Target: at most 2x.</item>
/// </list>
/// </summary>
internal static class ClothWorldCosts
{
    public static int Run(string[] args)
    {
        var rounds = Int(args, "--rounds", 7);
        if (args.Contains("--aerodynamics"))
        {
            return Aerodynamics(Int(args, "--n", 64), Int(args, "--frames", 120), rounds);
        }

        if (args.Contains("--self-collision"))
        {
            return SelfCollision(Int(args, "--n", 64), Int(args, "--frames", 120), Int(args, "--rounds", 3));
        }

        Console.Error.WriteLine("usage: cloth-world --aerodynamics | --self-collision [--n 64] [--frames 120] [--rounds 7] (see ClothWorldCosts)");
        return 2;
    }

    private static int Aerodynamics(int n, int frames, int rounds)
    {
        var still = MeshClothComparison.Build(n);
        var initial = still.System.State.ToArray();
        var xpbd = new Xpbd(XpbdCloth.Substeps);
        void Frames(TriangleCloth cloth)
        {
            cloth.System.SetState(initial);
            cloth.System.Time = 0;
            for (var f = 0; f < frames; f++)
            {
                cloth.System.Step(xpbd, XpbdCloth.FrameTime);
            }
        }

        Console.WriteLine(string.Create(CultureInfo.InvariantCulture,
            $"n = {n}: {still.Mesh.TriangleCount} triangles, xpbd {XpbdCloth.Substeps} substeps, {frames} frames of 1/60 s per round, {rounds} alternating rounds, one core; 5 m/s across the cloth, C_d 1.2, C_l 0.5"));
        var steady = new Air(1.2, new Vector3d(0, 0, 5), 1.2, 0.5);
        var gusty = new Air(1.2, new Vector3d(0, 0, 5), 1.2, 0.5) { Gust = new Gust(new GustWave(new Vector3d(1, 0.5, 0), 0.7, new Vector3d(0, 0, 0.9))) };
        var dragOnly = new Air(1.2, new Vector3d(0, 0, 5), 1.2, 0.0);
        foreach (var (name, air) in new[] { ("steady wind", steady), ("steady wind, drag only (C_l 0)", dragOnly), ("with a gust of one wave", gusty) })
        {
            var windy = MeshClothComparison.Build(n);
            var aerodynamics = new TriangleAerodynamics(windy.System, air);
            new MeshClothBuilder(windy.Mesh).AddTriangles(windy.FirstParticle, aerodynamics);
            windy.System.AddForce(aerodynamics);

            // The aerodynamics alone, at the windy cloth's state after the frames: one evaluation per substep of a frame.
            var forces = new double[3 * windy.System.Count];
            void Evaluations()
            {
                var state = windy.System.View();
                for (var e = 0; e < frames * XpbdCloth.Substeps; e++)
                {
                    aerodynamics.AddForces(state, forces);
                }
            }

            var (withoutAir, withAir) = MeshClothComparison.Alternate(() => Frames(still), () => Frames(windy), rounds);
            Frames(windy);
            var (stillAgain, alone) = MeshClothComparison.Alternate(() => Frames(still), Evaluations, rounds);
            var perFrame = 1.0 / frames;
            Console.WriteLine($"  {name}:");
            Console.WriteLine(string.Create(CultureInfo.InvariantCulture,
                $"    frame without air {withoutAir.Min() * perFrame:F3} ms (median {Rounds.Median(withoutAir) * perFrame:F3}), in the wind {withAir.Min() * perFrame:F3} ms (median {Rounds.Median(withAir) * perFrame:F3}): "
                + $"{withAir.Min() / withoutAir.Min():F3} fastest, {Rounds.MedianRatio(withAir, withoutAir):F3} median"));
            Console.WriteLine(string.Create(CultureInfo.InvariantCulture,
                $"    aerodynamics alone {alone.Min() * perFrame:F3} ms a frame ({alone.Min() * 1e6 / (frames * XpbdCloth.Substeps * (double)windy.Mesh.TriangleCount):F2} ns per triangle per substep): "
                + $"{100 * alone.Min() / stillAgain.Min():F1} % of the still frame (median of rounds {100 * Rounds.MedianRatio(alone, stillAgain):F1} %); target at most 10 %"));
        }

        return 0;
    }

    private static int SelfCollision(int n, int frames, int rounds)
    {
        const double thickness = 0.01;
        (TriangleCloth Cloth, ClothSelfCollision? Self) Drop(bool self)
        {
            var (vertices, triangles) = (new double[3 * n * n], new ClothMesh(n, n).CreateTriangles());
            var half = 0.5 * 0.025 * (n - 1);
            for (var i = 0; i < n * n; i++)
            {
                vertices[3 * i] = ((i % n) * 0.025) - half + 0.05;
                vertices[(3 * i) + 1] = 0.7;
                vertices[(3 * i) + 2] = ((i / n) * 0.025) - half + 0.07;
            }

            var cloth = new MeshClothBuilder(new WeldedMesh(vertices, triangles)) { AreaDensity = 0.2, Modulus = 1000, Poisson = 0.3, BendingRigidity = 1e-5 }.Build();
            var world = cloth.System;
            for (var i = 0; i < world.Count; i++)
            {
                world.SetRadius(i, thickness / 2);
            }

            ClothSelfCollision? collision = null;
            if (self)
            {
                collision = new ClothSelfCollision(world, cloth.Mesh.ParticleTriangles, thickness);
                world.AddConstraints(collision);
            }

            var obstacles = new ContactSet();
            obstacles.Add(PlaneObstacle.Ground(friction: 0.5));
            obstacles.Add(new SphereObstacle(new Vector3d(0, 0.3, 0), 0.3, friction: 0.5));
            world.AddConstraints(obstacles);
            return (cloth, collision);
        }

        var xpbd = new Xpbd(XpbdCloth.Substeps);
        long contacts = 0;
        void Frames(bool self)
        {
            var (cloth, collision) = Drop(self);
            for (var f = 0; f < frames; f++)
            {
                cloth.System.Step(xpbd, XpbdCloth.FrameTime);
                contacts += collision?.LastContactCount ?? 0;
            }
        }

        Console.WriteLine(string.Create(CultureInfo.InvariantCulture,
            $"n = {n}: {n * n} particles, {2 * (n - 1) * (n - 1)} triangles, thickness {thickness} m, xpbd {XpbdCloth.Substeps} substeps, {frames} frames of 1/60 s per round, {rounds} alternating rounds, one core; dropped onto a sphere and the floor"));
        var (without, with) = MeshClothComparison.Alternate(() => Frames(false), () => Frames(true), rounds);
        var perFrame = 1.0 / frames;
        Console.WriteLine(string.Create(CultureInfo.InvariantCulture,
            $"  frame without self-collision {without.Min() * perFrame:F3} ms (median {Rounds.Median(without) * perFrame:F3}), with it {with.Min() * perFrame:F3} ms (median {Rounds.Median(with) * perFrame:F3}): "
            + $"{with.Min() / without.Min():F2}x fastest, {Rounds.MedianRatio(with, without):F2}x median; target at most 2x; {contacts / Math.Max(1, rounds)} self-contacts projected per round"));
        return 0;
    }

    private static int Int(string[] args, string name, int fallback) =>
        int.Parse(Program.Option(args, name) ?? fallback.ToString(CultureInfo.InvariantCulture), CultureInfo.InvariantCulture);
}
