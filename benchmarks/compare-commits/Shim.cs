using System;
using System.Diagnostics;
using ParticlePhysics;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;

/// <summary>
/// One side of run.sh, compiled against one library (so it uses only what every library since issue 12 has): the
/// n x n cloth from rest, one integrator of the catalog taking <c>steps</c> steps per 60 Hz frame (implicit Euler at
/// a tolerance, with that library's default preconditioner); <see cref="Round"/> runs one simulated second from rest
/// and returns its wall time in milliseconds. The host calls it by reflection (plain types only), so that two
/// libraries can run in one process. With RUNNER=p in the environment the world steps on a WorkerThreadRunner(p) of
/// its library (found by name: a library without one fails).
/// </summary>
public sealed class Shim : IDisposable
{
    private readonly ParticleWorld _world;
    private readonly double[] _initial;
    private readonly IIntegrator _integrator;
    private readonly double[]? _coldState;
    private readonly int _steps;
    private readonly IDisposable? _runner;

    /// <summary>The n x n cloth and <paramref name="integrator"/> (implicit Euler at <paramref name="tolerance"/>), <paramref name="steps"/> steps per frame.</summary>
    public Shim(int n, double tolerance, string integrator, int steps)
    {
        _world = new ClothScenario { Resolution = 1.0 / (n - 1) }.Build();
        _initial = _world.State.ToArray();
        _integrator = IntegratorCatalog.Create(integrator);
        if (_integrator is ImplicitEuler implicitEuler)
        {
            implicitEuler.Tolerance = tolerance;
        }

        // A round starts the integrator cold, as a new simulation would: the state of a fresh one, read back each round.
        if (_integrator is IStatefulIntegrator stateful)
        {
            _coldState = new double[stateful.StateLength];
            stateful.WriteState(_coldState);
        }

        _steps = steps;
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

    /// <summary>The conjugate-gradient iterations of the last round (implicit Euler; 0 for the others).</summary>
    public long Iterations { get; private set; }

    /// <summary>FNV-1a of the raw bits of the state after the last round: equal on both sides when both compute the same cloth.</summary>
    public ulong StateHash
    {
        get
        {
            var hash = 14695981039346656037UL;
            foreach (var value in _world.State)
            {
                var bits = BitConverter.DoubleToInt64Bits(value);
                for (var b = 0; b < 64; b += 8)
                {
                    hash = (hash ^ (ulong)((bits >> b) & 0xff)) * 1099511628211UL;
                }
            }

            return hash;
        }
    }

    /// <summary>One simulated second (60 frames) from rest; the wall time in milliseconds.</summary>
    public double Round()
    {
        _world.SetState(_initial);
        _world.Time = 0;
        if (_coldState is not null)
        {
            ((IStatefulIntegrator)_integrator).ReadState(_coldState);
        }

        Iterations = 0;
        var dt = 1.0 / 60 / _steps;
        var clock = Stopwatch.StartNew();
        for (var f = 0; f < 60; f++)
        {
            for (var s = 0; s < _steps; s++)
            {
                _world.Step(_integrator, dt);
            }

            Iterations += (_integrator as ImplicitEuler)?.LastIterations ?? 0;
        }

        return clock.Elapsed.TotalMilliseconds;
    }
}
