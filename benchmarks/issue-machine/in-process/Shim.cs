using System;
using System.Diagnostics;
using ParticlePhysics;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;

/// <summary>
/// One side of in-process.sh, compiled against one library (so it uses only what every library since the issue has):
/// the 64 x 64 cloth at 60 Hz from rest with implicit Euler (that library's default preconditioner) at a tolerance;
/// <see cref="Round"/> runs one simulated second from rest and returns its wall time in milliseconds. The host calls
/// it by reflection (plain types only), so that two libraries can run in one process. With RUNNER=p in the
/// environment the world steps on a WorkerThreadRunner(p) of its library (found by name: a library without one fails).
/// </summary>
public sealed class Shim : IDisposable
{
    private readonly ParticleWorld _world;
    private readonly double[] _initial;
    private readonly ImplicitEuler _implicitEuler;
    private readonly IDisposable? _runner;

    /// <summary>The n x n cloth and implicit Euler at <paramref name="tolerance"/>.</summary>
    public Shim(int n, double tolerance)
    {
        _world = new ClothScenario { Resolution = 1.0 / (n - 1) }.Build();
        _initial = _world.State.ToArray();
        _implicitEuler = new ImplicitEuler { Tolerance = tolerance };
        if (int.TryParse(Environment.GetEnvironmentVariable("RUNNER"), out var threads) && threads > 1)
        {
            var type = typeof(ParticleWorld).Assembly.GetType("ParticlePhysics.Parallel.WorkerThreadRunner")
                ?? throw new InvalidOperationException("RUNNER is set, but this library has no WorkerThreadRunner.");
            _runner = (IDisposable)Activator.CreateInstance(type, threads)!;
            typeof(ParticleWorld).GetProperty("Runner")!.SetValue(_world, _runner);
        }
    }

    /// <summary>Stops the runner's threads, if any.</summary>
    public void Dispose() => _runner?.Dispose();

    /// <summary>The CG iterations of the last round.</summary>
    public long Iterations { get; private set; }

    /// <summary>One simulated second (60 frames) from rest; the wall time in milliseconds.</summary>
    public double Round()
    {
        _world.SetState(_initial);
        _world.Time = 0;
        _implicitEuler.ReadState(new double[] { 0 });
        Iterations = 0;
        var clock = Stopwatch.StartNew();
        for (var f = 0; f < 60; f++)
        {
            _world.Step(_implicitEuler, 1.0 / 60);
            Iterations += _implicitEuler.LastIterations;
        }

        return clock.Elapsed.TotalMilliseconds;
    }
}
