using System;
using System.Diagnostics;
using System.Globalization;
using System.Linq;
using ParticlePhysics.Cloth;
using ParticlePhysics.Contacts;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// <c>colliders [--levels 3,4,5,6,7,8] [--steps 120] [--rays 100000]</c>: the cost of triangle mesh colliders, outside
/// BenchmarkDotNet (a mesh of a million triangles takes seconds to build). For each level k, a geodesic sphere of
/// 20 4^k triangles (1,280 to 1,310,720) and radius 0.4 m; a cloth of 64 x 64 particles (radius 1 cm, 2.5 cm apart) is
/// dropped onto it and stepped at 60 Hz under xpbd (10 substeps); the contact stage's time per step
/// (<see cref="StepProfile.ContactSeconds"/>, the obstacle broad phase within it) is the median over the steps after
/// the first second, when the cloth lies draped (the particles then within 5 mm of touching are counted). Then rays from random points 2 m from the centre towards random points
/// within the sphere: the mean time of one <see cref="ContactSet.Raycast"/>.
/// </summary>
internal static class ColliderCosts
{
    public static int Run(string[] args)
    {
        var levels = Option(args, "--levels", "3,4,5,6,7,8").Split(',').Select(s => int.Parse(s, CultureInfo.InvariantCulture)).ToArray();
        var steps = int.Parse(Option(args, "--steps", "120"), CultureInfo.InvariantCulture);
        var rays = int.Parse(Option(args, "--rays", "100000"), CultureInfo.InvariantCulture);
        Console.WriteLine("triangles  build_s  contact_ms_per_step  broad_phase_ms  touching  ray_us  hits");
        foreach (var level in levels)
        {
            var clock = Stopwatch.StartNew();
            StandardMeshes.Icosphere(0.4, level, out var vertices, out var triangles);
            var sphere = new MeshObstacle(vertices, triangles, friction: 0.5) { Position = new Vector3d(0.8, -0.5, 0.8) };
            var build = clock.Elapsed.TotalSeconds;

            var world = new ParticleWorld();
            var cloth = new ClothBuilder { Rows = 64, Columns = 64, Spacing = 0.025, Pinning = ClothPinning.None }.AddTo(world);
            for (var i = 0; i < world.Count; i++)
            {
                world.SetRadius(i, 0.01);
            }

            world.AddForce(Forces.Gravity.Down(9.81));
            var contacts = new ContactSet();
            contacts.Add(sphere);
            world.AddConstraints(contacts);
            world.Profiling = true;
            var xpbd = new Xpbd { Substeps = 10 };
            var contactTimes = new double[steps];
            var broadTimes = new double[steps];
            for (var s = 0; s < 60 + steps; s++)
            {
                world.Step(xpbd, 1.0 / 60.0);
                if (s >= 60)
                {
                    var profile = world.LastStepProfile;
                    contactTimes[s - 60] = profile.ContactSeconds;
                    broadTimes[s - 60] = profile.BroadPhaseSeconds;
                }
            }

            var touching = 0;
            for (var i = 0; i < world.Count; i++)
            {
                touching += sphere.SignedDistance(world.GetPosition(i), out _) < 0.015 ? 1 : 0;
            }

            var random = new Random(31);
            var origins = new Vector3d[rays];
            var directions = new Vector3d[rays];
            for (var r = 0; r < rays; r++)
            {
                origins[r] = sphere.Position + (2.0 * Unit(random));
                directions[r] = sphere.Position + (0.3 * Unit(random)) - origins[r];
            }

            var hits = 0;
            clock.Restart();
            for (var r = 0; r < rays; r++)
            {
                hits += contacts.Raycast(null, origins[r], directions[r], 10.0, out _) ? 1 : 0;
            }

            var rayMicroseconds = clock.Elapsed.TotalSeconds * 1e6 / rays;
            Console.WriteLine(string.Format(
                CultureInfo.InvariantCulture,
                "{0,9:N0}  {1,7:F2}  {2,19:F3}  {3,14:F3}  {4,8}  {5,6:F2}  {6}",
                sphere.TriangleCount,
                build,
                1e3 * Median(contactTimes),
                1e3 * Median(broadTimes),
                touching,
                rayMicroseconds,
                hits));
            GC.KeepAlive(cloth);
        }

        return 0;
    }

    private static Vector3d Unit(Random random)
    {
        while (true)
        {
            var v = new Vector3d((2 * random.NextDouble()) - 1, (2 * random.NextDouble()) - 1, (2 * random.NextDouble()) - 1);
            var length = v.Length;
            if (length > 0.1 && length <= 1.0)
            {
                return v / length;
            }
        }
    }

    private static double Median(double[] values)
    {
        var sorted = (double[])values.Clone();
        Array.Sort(sorted);
        return sorted[sorted.Length / 2];
    }

    private static string Option(string[] args, string name, string defaultValue)
    {
        var at = Array.IndexOf(args, name);
        return at >= 0 && at + 1 < args.Length ? args[at + 1] : defaultValue;
    }
}
