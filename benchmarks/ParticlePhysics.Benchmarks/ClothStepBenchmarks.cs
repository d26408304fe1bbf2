using System.Collections.Generic;
using BenchmarkDotNet.Attributes;
using ParticlePhysics.Benchmarks.Columns;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// Issue 5, item 1: one RK4 step of the n x n cloth, for n = 16 to 256, at dt = 1 ms up to n = 64 and inside RK4's
/// stability limit beyond (<see cref="ClothFixture.Rk4TimeStep"/>: 1 ms diverges at n = 128). Each invocation resets the
/// cloth and runs <see cref="ClothFixture.StepsPerInvoke"/> steps (see <see cref="ClothFixture"/> for why); the
/// <c>Reset</c> row is the share of that reset in each step, to subtract if it matters.
/// </summary>
[MemoryDiagnoser]
[Config(typeof(ClothColumnsConfig))]
public class ClothStepBenchmarks
{
    private readonly RungeKutta4 _rk4 = new();
    private ClothFixture _cloth = null!;

    [ParamsSource(nameof(Sizes))]
    public int N { get; set; }

    public static IEnumerable<int> Sizes => BenchmarkSizes.Scaling;

    [GlobalSetup]
    public void Setup()
    {
        _cloth = new ClothFixture(N);

        // One step sizes the integrator's and the system's scratch buffers, so that no invocation allocates them.
        _cloth.System.Step(_rk4, _cloth.TimeStep);
        _cloth.Reset();
    }

    [Benchmark(OperationsPerInvoke = ClothFixture.StepsPerInvoke, Description = "RK4 step")]
    [ClothWork(4)]
    public void Rk4Step()
    {
        _cloth.Reset();
        for (var s = 0; s < ClothFixture.StepsPerInvoke; s++)
        {
            _cloth.System.Step(_rk4, _cloth.TimeStep);
        }
    }

    [Benchmark(OperationsPerInvoke = ClothFixture.StepsPerInvoke, Description = "Reset (share per step)")]
    public void Reset() => _cloth.Reset();
}
