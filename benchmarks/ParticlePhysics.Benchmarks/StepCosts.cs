using System;
using System.Diagnostics;
using System.Globalization;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The <c>costs</c> mode: what one step costs per step, per particle and per spring, for each integrator, measured on
/// three worlds at the demo's default cloth step (1 ms): one free particle (gravity and drag), 4,096 free particles,
/// and the 64 x 64 cloth (4,096 particles, 23,938 springs). Each time is the fastest of many short batches, which is
/// what a loaded machine gets closest to its quiet speed with. The demo's run-cost estimate
/// (samples/ParticlePhysics.Demo/Running/RunCost.cs) takes its constants from this table.
/// </summary>
internal static class StepCosts
{
    private const double Dt = 0.001;

    public static int Run(string[] args)
    {
        var batches = args.Length > 0 ? int.Parse(args[0], CultureInfo.InvariantCulture) : 200;
        Console.WriteLine("| integrator | per step [ns] | per particle [ns] | per spring [ns] | 4096 particles [us] | 64 x 64 cloth [us] |");
        Console.WriteLine("| --- | ---: | ---: | ---: | ---: | ---: |");
        foreach (var name in IntegratorCatalog.Names)
        {
            var one = Fastest(FreeParticles(1), name, 2000, batches);
            var many = Fastest(FreeParticles(4096), name, 4, batches);
            var cloth = new ClothScenario { Resolution = 1.0 / 63 }.Build();
            var springs = ClothScenario.SpringCount(64);
            var clothStep = Fastest(cloth, name, 2, batches);
            var perParticle = (many - one) / 4095;
            var perSpring = (clothStep - one - (4096 * perParticle)) / springs;
            Console.WriteLine(string.Create(
                CultureInfo.InvariantCulture,
                $"| {name} | {one * 1e9:F0} | {perParticle * 1e9:F2} | {perSpring * 1e9:F2} | {many * 1e6:F1} | {clothStep * 1e6:F1} |"));
        }

        return 0;
    }

    private static ParticleWorld FreeParticles(int n)
    {
        var world = new ParticleWorld(n);
        for (var i = 0; i < n; i++)
        {
            world.AddParticle(new Vector3d(0.01 * i, 300, 0), 0.01);
        }

        world.AddForce(new Gravity());
        world.AddForce(new LinearDrag(0.01));
        return world;
    }

    /// <summary>The fastest time of one step over <paramref name="batches"/> batches of <paramref name="steps"/> steps from the same state.</summary>
    private static double Fastest(ParticleWorld world, string integrator, int steps, int batches)
    {
        var method = IntegratorCatalog.Create(integrator);
        world.Step(method, Dt); // warm-up: JIT, scratch buffers
        var start = world.State.ToArray();
        var best = double.MaxValue;
        for (var batch = 0; batch < batches; batch++)
        {
            world.SetState(start);
            world.Time = 0;
            var clock = Stopwatch.StartNew();
            for (var s = 0; s < steps; s++)
            {
                world.Step(method, Dt);
            }

            best = Math.Min(best, clock.Elapsed.TotalSeconds / steps);
        }

        return best;
    }
}
