using System.Collections.Generic;
using BenchmarkDotNet.Attributes;
using ParticlePhysics.Benchmarks.Stability;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// Issue 5, item 2: every integrator of <see cref="IntegratorCatalog.Names"/> on the 64 x 64 cloth, each at its
/// largest stable time step (found by the stability mode, saved in stable-time-steps.csv): the cost of one step,
/// and the cost of one simulated second from rest. rk45 is adaptive: it runs at its default tolerance (1e-8), with
/// dt as its output interval. Computed columns: dt, and ms of wall time per simulated second.
/// </summary>
[MemoryDiagnoser]
[Config(typeof(IntegratorColumnsConfig))]
public class IntegratorBenchmarks
{
    private ClothFixture _cloth = null!;
    private IIntegrator _integrator = null!;
    private double _dt;
    private int _stepsPerSecond;

    [ParamsSource(nameof(Names))]
    public string Integrator { get; set; } = IntegratorCatalog.DefaultName;

    public static IEnumerable<string> Names => IntegratorCatalog.Names;

    /// <summary>The time step of an integrator in these benchmarks: its largest stable dt, rounded to whole steps per second.</summary>
    public static double TimeStepFor(string integrator) =>
        StableTimeSteps.Rounded(StableTimeSteps.For(integrator, BenchmarkSizes.IntegratorCloth));

    [GlobalSetup]
    public void Setup()
    {
        _cloth = new ClothFixture(BenchmarkSizes.IntegratorCloth);
        _integrator = IntegratorCatalog.Create(Integrator);
        _dt = TimeStepFor(Integrator);
        _stepsPerSecond = (int)System.Math.Round(1.0 / _dt);
        _cloth.System.Step(_integrator, _dt);
        _cloth.Reset();
    }

    [Benchmark(OperationsPerInvoke = ClothFixture.StepsPerInvoke)]
    public void Step()
    {
        _cloth.Reset();
        for (var s = 0; s < ClothFixture.StepsPerInvoke; s++)
        {
            _cloth.System.Step(_integrator, _dt);
        }
    }

    [Benchmark]
    public void SimulatedSecond()
    {
        _cloth.Reset();
        if (_integrator is DormandPrince45 adaptive)
        {
            adaptive.CurrentStepSize = 0; // start its step-size control afresh, as a new simulation would
        }

        for (var s = 0; s < _stepsPerSecond; s++)
        {
            _cloth.System.Step(_integrator, _dt);
        }
    }
}
