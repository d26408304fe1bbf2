using System.Collections.Generic;
using BenchmarkDotNet.Attributes;
using ParticlePhysics.Benchmarks.Columns;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// Suggestion 1 of docs/benchmarks.md measured on a whole RK4 step: the library's cloth step (baseline) against the
/// same system with its spring network swapped for <see cref="PackedSprings"/>, bit-identical results. Same reset
/// and time step as <see cref="ClothStepBenchmarks"/>.
/// </summary>
[MemoryDiagnoser]
[Config(typeof(ClothColumnsConfig))]
public class PackedStepBenchmarks
{
    private readonly RungeKutta4 _rk4 = new();
    private readonly RungeKutta4 _packedRk4 = new();
    private ClothFixture _library = null!;
    private ClothFixture _packed = null!;

    [ParamsSource(nameof(Sizes))]
    public int N { get; set; }

    public static IEnumerable<int> Sizes => BenchmarkSizes.Kernel;

    [GlobalSetup]
    public void Setup()
    {
        _library = new ClothFixture(N);
        _packed = new ClothFixture(N);
        PackedSprings.Replace(_packed.System, _packed.Scenario.Stiffness, _packed.Scenario.Damping);
        _library.System.Step(_rk4, _library.TimeStep);
        _library.Reset();
        _packed.System.Step(_packedRk4, _packed.TimeStep);
        _packed.Reset();
    }

    [Benchmark(Baseline = true, OperationsPerInvoke = ClothFixture.StepsPerInvoke, Description = "RK4 step, SpringNetwork")]
    [ClothWork(4)]
    public void Library() => Run(_library, _rk4);

    [Benchmark(OperationsPerInvoke = ClothFixture.StepsPerInvoke, Description = "RK4 step, packed springs")]
    [ClothWork(4)]
    public void Packed() => Run(_packed, _packedRk4);

    private static void Run(ClothFixture cloth, RungeKutta4 rk4)
    {
        cloth.Reset();
        for (var s = 0; s < ClothFixture.StepsPerInvoke; s++)
        {
            cloth.System.Step(rk4, cloth.TimeStep);
        }
    }
}
