using System;
using System.Diagnostics;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;

// The program of run.sh, compiled against the library of then and of now (so it uses only what both have): one
// simulated second of the 64 x 64 cloth at 60 Hz from rest with implicit Euler at 1e-3 (each library's default
// preconditioner) per round; one world and one integrator, reset between rounds as the benchmarks do; 3 rounds of
// warm-up, then the fastest and the median of the timed rounds.
var rounds = int.Parse(args[0]);
var world = new ClothScenario { Resolution = 1.0 / 63 }.Build();
var initial = world.State.ToArray();
var ie = new ImplicitEuler { Tolerance = 1e-3 };
var times = new System.Collections.Generic.List<double>();
long iterations = 0;
for (var round = -3; round < rounds; round++)
{
    world.SetState(initial);
    world.Time = 0;
    ie.ReadState(new double[] { 0 });
    iterations = 0;
    var clock = Stopwatch.StartNew();
    for (var f = 0; f < 60; f++)
    {
        world.Step(ie, 1.0 / 60);
        iterations += ie.LastIterations;
    }

    if (round >= 0)
    {
        times.Add(clock.Elapsed.TotalMilliseconds);
    }
}

times.Sort();
Console.WriteLine(FormattableString.Invariant($"{Environment.GetEnvironmentVariable("LABEL")}: fastest {times[0]:F1} ms, median {times[times.Count / 2]:F1} ms, {iterations / 60.0:F2} it/frame"));
