using System;
using System.Diagnostics;
using System.Globalization;
using System.Linq;
using ParticlePhysics.Contacts;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The sleep mode (issue 32): <c>sleep [--grains 10000] [--seconds 12] [--substeps 20] [--sleep-speed 0.05]</c>. A
/// block of grains of 1 cm (friction 0.6, rolling friction 0.3) falls from 10 cm into a box of 0.6 m at 60 Hz. It prints
/// the cost per step of the first second (falling) and of the last second, and their ratio (the target: a settled pile
/// at most 10 % of a falling one); it fails unless 99 % of the grains sleep before the last second.
/// </summary>
internal static class SleepingPile
{
    public static int Run(string[] args)
    {
        var grains = Int(args, "--grains", 10000);
        var seconds = Int(args, "--seconds", 12);
        var substeps = Int(args, "--substeps", 20);
        var sleepSpeed = Double(args, "--sleep-speed", 0.05);
        const double dt = 1.0 / 60, r = 0.01;
        var world = new ParticleWorld { SleepSpeed = sleepSpeed };
        world.AddForce(Gravity.Down(9.81));
        var side = (int)Math.Min(22, Math.Ceiling(Math.Sqrt(grains / 12.0))); // 22 x 2.5 cm fits the box
        ulong seed = 12345;
        double Jitter()
        {
            seed = (seed * 6364136223846793005UL) + 1442695040888963407UL;
            return ((seed >> 11) * (1.0 / (1UL << 53))) - 0.5;
        }

        for (var i = 0; i < grains; i++)
        {
            // Layers of side x side grains 2.5 cm apart, each moved by up to 2 mm at random, dropped from 10 cm up.
            var column = i % (side * side);
            var layer = i / (side * side);
            var p = world.AddParticle(
                new Vector3d(
                    (0.025 * ((column % side) - (0.5 * (side - 1)))) + (0.004 * Jitter()),
                    0.1 + (0.025 * layer) + (0.004 * Jitter()),
                    (0.025 * ((column / side) - (0.5 * (side - 1)))) + (0.004 * Jitter())),
                0.004);
            world.SetRadius(p, r);
        }

        var contacts = new ContactSet { ParticleCollisions = true };
        contacts.SetGranular(0, grains, 0.6, 0.3);
        contacts.Add(PlaneObstacle.Ground(0, 1.0));
        contacts.Add(new PlaneObstacle(new Vector3d(-0.3, 0, 0), new Vector3d(1, 0, 0), 0, 0.5));
        contacts.Add(new PlaneObstacle(new Vector3d(0.3, 0, 0), new Vector3d(-1, 0, 0), 0, 0.5));
        contacts.Add(new PlaneObstacle(new Vector3d(0, 0, -0.3), new Vector3d(0, 0, 1), 0, 0.5));
        contacts.Add(new PlaneObstacle(new Vector3d(0, 0, 0.3), new Vector3d(0, 0, -1), 0, 0.5));
        world.AddConstraints(contacts);
        var xpbd = new Xpbd(substeps);
        var steps = (int)(seconds / dt);
        var watch = new Stopwatch();
        double falling = 0, settled = 0;
        var asleepAt = -1;
        var profile = default(StepProfile);
        for (var step = 0; step < steps; step++)
        {
            watch.Restart();
            world.Step(xpbd, dt);
            var elapsed = watch.Elapsed.TotalMilliseconds;
            if (step >= 5 && step < 65)
            {
                falling += elapsed / 60; // the first second after the warm-up steps
            }

            if (asleepAt < 0 && world.SleepingCount >= 0.99 * grains)
            {
                asleepAt = step;
            }

            if (step >= steps - 60)
            {
                settled += elapsed / 60;
            }
        }

        // One more second, profiled, for where the settled pile's time goes (apart from the timed steps, which the
        // profile's clock reads would slow).
        world.Profiling = true;
        for (var step = 0; step < 60; step++)
        {
            world.Step(xpbd, dt);
            profile += world.LastStepProfile;
        }

        Console.WriteLine(string.Create(
            CultureInfo.InvariantCulture,
            $"sleep: {grains} grains, {substeps} substeps, sleep speed {sleepSpeed} m/s, one core; 99 % asleep after {(asleepAt < 0 ? "never" : ((asleepAt + 1) * dt).ToString("F2", CultureInfo.InvariantCulture) + " s")}; {world.SleepingCount} asleep at the end"));
        Console.WriteLine(string.Create(
            CultureInfo.InvariantCulture,
            $"  falling {falling:F2} ms per step, settled (last second) {settled:F2} ms per step: {100 * settled / falling:F1} % (target 10 %)"));
        Console.WriteLine(string.Create(
            CultureInfo.InvariantCulture,
            $"  settled, profiled a second more, per step: contacts {1e3 * profile.ContactSeconds / 60:F2} ms (broad phase {1e3 * profile.BroadPhaseSeconds / 60:F2} ms), other sets {1e3 * profile.ConstraintSeconds / 60:F2} ms, forces {1e3 * profile.ForceSeconds / 60:F2} ms, integration {1e3 * profile.IntegrationSeconds / 60:F2} ms"));
        return asleepAt < 0 || asleepAt >= steps - 60 ? 1 : 0;
    }

    private static double Double(string[] args, string name, double fallback)
    {
        var i = Array.IndexOf(args, name);
        return i >= 0 && i + 1 < args.Length ? double.Parse(args[i + 1], CultureInfo.InvariantCulture) : fallback;
    }

    private static int Int(string[] args, string name, int fallback)
    {
        var i = Array.IndexOf(args, name);
        return i >= 0 && i + 1 < args.Length ? int.Parse(args[i + 1], CultureInfo.InvariantCulture) : fallback;
    }
}
