using System.Collections.Generic;
using BenchmarkDotNet.Attributes;
using ParticlePhysics.Benchmarks.Columns;
using ParticlePhysics.Integrators;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// Issue 5: one RK4 cloth step on one core (the baseline) and with a <see cref="WorkerThreadRunner"/> of 2
/// (this machine's cores), whose results are bit-identical (the tests check it). Target: at least 1.6x on the
/// 128 x 128 cloth.
/// </summary>
[MemoryDiagnoser]
[Config(typeof(ClothColumnsConfig))]
public class ParallelBenchmarks
{
    private readonly RungeKutta4 _rk4 = new();
    private WorkerThreadRunner _runner = null!;
    private ClothFixture _cloth = null!;

    [ParamsSource(nameof(Sizes))]
    public int N { get; set; }

    public static IEnumerable<int> Sizes => BenchmarkSizes.Parallel;

    [GlobalSetup]
    public void Setup()
    {
        _cloth = new ClothFixture(N);
        _runner = new WorkerThreadRunner(2);
        _cloth.System.Runner = _runner;
        _cloth.System.Step(_rk4, _cloth.TimeStep); // sizes the scratch buffers
        _cloth.System.Runner = null;
        _cloth.System.Step(_rk4, _cloth.TimeStep);
        _cloth.Reset();
    }

    [GlobalCleanup]
    public void Cleanup() => _runner.Dispose();

    [Benchmark(Baseline = true, OperationsPerInvoke = ClothFixture.StepsPerInvoke, Description = "RK4 step, one core")]
    [ClothWork(4)]
    public void OneCore() => Run(null);

    [Benchmark(OperationsPerInvoke = ClothFixture.StepsPerInvoke, Description = "RK4 step, WorkerThreadRunner(2)")]
    [ClothWork(4)]
    public void TwoCores() => Run(_runner);

    private void Run(IParallelRunner? runner)
    {
        _cloth.Reset();
        _cloth.System.Runner = runner;
        for (var s = 0; s < ClothFixture.StepsPerInvoke; s++)
        {
            _cloth.System.Step(_rk4, _cloth.TimeStep);
        }
    }
}
