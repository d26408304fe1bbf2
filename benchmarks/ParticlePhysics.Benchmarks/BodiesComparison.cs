using System;
using System.Globalization;
using System.Linq;
using ParticlePhysics.Bodies;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The bodies mode (issue 32): <c>bodies --c [--bodies 100] [--side 4] [--passes 200] [--rounds 5]</c>, the rigid
/// bodies' shape matching (<see cref="ShapeMatching"/>'s projection and velocity pass, one of each per substep) against
/// its plain C reference (<see cref="NativeShapeMatching"/>) on the same arrays, after a bit-for-bit check of three
/// passes: 100 boxes of 4 x 4 x 4 particles, spinning, in alternating rounds; the fastest round of each side with the
/// median of the per-round ratios.
/// </summary>
internal static class BodiesComparison
{
    public static int Run(string[] args)
    {
        if (!args.Contains("--c"))
        {
            Console.Error.WriteLine("usage: bodies --c [--bodies 100] [--side 4] [--passes 200] [--rounds 5] (see BodiesComparison)");
            return 2;
        }

        var bodies = Int(args, "--bodies", 100);
        var side = Int(args, "--side", 4);
        var passes = Int(args, "--passes", 200);
        var rounds = Int(args, "--rounds", 5);
        var per = side * side * side;
        const double h = 1.0 / 600;

        // Boxes 10 cm apart on a row of tens, each spinning about its own tilted axis and moving, so that every pass
        // turns every body and the extraction iterates from its warm start.
        var world = new ParticleWorld();
        var set = new ShapeMatching(world);
        var offsets = BodyLattice.BoxOffsets(new Vector3d(0.1 * side, 0.1 * side, 0.1 * side), 0.1);
        for (var b = 0; b < bodies; b++)
        {
            var centre = new Vector3d(0.6 * side * (b % 10), 0.6 * side * (b / 10), 0);
            var particles = new int[per];
            for (var k = 0; k < per; k++)
            {
                particles[k] = world.AddParticle(centre + offsets[k], 0.01 * (1 + (k % 3)));
            }

            set.AddRigid(particles);
            set.SetMotion(b, new Vector3d(0.1 * (b % 3), -0.2, 0.05), new Vector3d(1 + (b % 3), 2 - (0.3 * (b % 5)), 0.5 + (0.1 * (b % 7))));
        }

        world.AddConstraints(set);
        var n = world.Count;
        var x0 = world.Positions.ToArray();
        var v0 = world.Velocities.ToArray();
        var m = world.Masses.ToArray();
        var w = world.InverseMasses.ToArray();
        var start = x0.Select((p, i) => p + (h * v0[i])).ToArray();
        var rest = new double[3 * n];
        var entries = new int[n];
        for (var b = 0; b < bodies; b++)
        {
            var shape = set.RestShapeOf(b);
            set.ParticlesOf(b).CopyTo(entries.AsSpan(b * per, per));
            for (var k = 0; k < per; k++)
            {
                rest[3 * ((b * per) + k)] = shape[k].X;
                rest[(3 * ((b * per) + k)) + 1] = shape[k].Y;
                rest[(3 * ((b * per) + k)) + 2] = shape[k].Z;
            }
        }

        using var c = new NativeShapeMatching(bodies, per, entries, rest);
        var (xL, vL, xC, vC) = ((double[])start.Clone(), (double[])v0.Clone(), (double[])start.Clone(), (double[])v0.Clone());
        void Library(int count)
        {
            for (var p = 0; p < count; p++)
            {
                var context = new ConstraintContext(0, h, x0, v0, xL, vL, m, w);
                set.Project(context);
                set.SolveVelocities(context);
            }
        }

        set.BeginStep();
        Library(3);
        set.DiscardStep();
        c.Run(h, x0, xC, vC, m, w, 3);
        var same = xL.AsSpan().SequenceEqual(xC) && vL.AsSpan().SequenceEqual(vC);
        Console.WriteLine(string.Create(CultureInfo.InvariantCulture,
            $"{bodies} rigid bodies of {side} x {side} x {side} = {per} particles ({n} particles): {(same ? "same bits after three passes" : "DIFFERENT positions or velocities after three passes")}; {passes} passes (a projection and a velocity pass each) per round, {rounds} rounds"));
        var (a, bTimes) = MeshClothComparison.Alternate(
            () =>
            {
                start.CopyTo(xC, 0);
                v0.CopyTo(vC, 0);
                c.Reset();
                c.Run(h, x0, xC, vC, m, w, passes);
            },
            () =>
            {
                start.CopyTo(xL, 0);
                v0.CopyTo(vL, 0);
                set.BeginStep();
                Library(passes);
                set.DiscardStep();
            },
            rounds);
        var perParticle = 1e6 / ((double)passes * n);
        Console.WriteLine(string.Create(CultureInfo.InvariantCulture,
            $"  C {a.Min() * perParticle:F2} ns, library {bTimes.Min() * perParticle:F2} ns per particle per substep; library / C {bTimes.Min() / a.Min():F3}, median {Rounds.MedianRatio(bTimes, a):F3}"));
        return same ? 0 : 1;
    }

    private static int Int(string[] args, string name, int fallback) =>
        int.Parse(Program.Option(args, name) ?? fallback.ToString(CultureInfo.InvariantCulture), CultureInfo.InvariantCulture);
}
