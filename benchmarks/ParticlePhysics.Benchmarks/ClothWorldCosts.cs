using System;
using System.Globalization;
using System.Linq;
using ParticlePhysics.Aerodynamics;
using ParticlePhysics.Cloth;
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

        Console.Error.WriteLine("usage: cloth-world --aerodynamics [--n 64] [--frames 120] [--rounds 7] (see ClothWorldCosts)");
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

    private static int Int(string[] args, string name, int fallback) =>
        int.Parse(Program.Option(args, name) ?? fallback.ToString(CultureInfo.InvariantCulture), CultureInfo.InvariantCulture);
}
