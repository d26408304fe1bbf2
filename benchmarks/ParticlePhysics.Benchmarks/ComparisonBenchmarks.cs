using System.Collections.Generic;
using BenchmarkDotNet.Attributes;
using ParticlePhysics.Benchmarks.Columns;
using ParticlePhysics.Benchmarks.Student;
using ParticlePhysics.Integrators;
using MathNetVector = MathNet.Numerics.LinearAlgebra.Vector<double>;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// Issue 5, items 3 and 4: the same RK4 cloth steps (<see cref="ClothFixture.Rk4TimeStep"/>, <see cref="ClothFixture.StepsPerInvoke"/> steps
/// from rest per invocation) by the library (the baseline of the Ratio column), by Math.NET Numerics' RK4 on the
/// library's force code, and by the course student's object-per-particle code. Ratio = time / library time.
/// The "4 x Evaluate" row is the force work every RK4 step contains (four evaluations of the library's
/// <see cref="ParticleWorld.Evaluate"/> on the initial state): Math.NET calls that same code, so its time can never
/// fall below it, and (Math.NET - floor) / (library - floor) compares what each adds around the forces.
/// </summary>
[MemoryDiagnoser]
[Config(typeof(ClothColumnsConfig))]
public class ComparisonBenchmarks
{
    private readonly RungeKutta4 _rk4 = new();
    private ClothFixture _cloth = null!;
    private MathNetPeer _mathNet = null!;
    private MathNetVector _initial = null!;
    private StudentCloth _student = null!;
    private double[] _derivative = null!;

    [ParamsSource(nameof(Sizes))]
    public int N { get; set; }

    public static IEnumerable<int> Sizes => BenchmarkSizes.Comparison;

    [GlobalSetup]
    public void Setup()
    {
        _cloth = new ClothFixture(N);
        _cloth.System.Step(_rk4, _cloth.TimeStep);
        _cloth.Reset();
        _mathNet = new MathNetPeer(_cloth.System);
        _initial = MathNetVector.Build.DenseOfArray(_cloth.InitialState.ToArray());
        _student = new StudentCloth(N);
        _derivative = new double[_cloth.System.Dimension];
    }

    [Benchmark(Baseline = true, OperationsPerInvoke = ClothFixture.StepsPerInvoke, Description = "ParticlePhysics RK4")]
    [ClothWork(4)]
    public void Library()
    {
        _cloth.Reset();
        for (var s = 0; s < ClothFixture.StepsPerInvoke; s++)
        {
            _cloth.System.Step(_rk4, _cloth.TimeStep);
        }
    }

    [Benchmark(OperationsPerInvoke = ClothFixture.StepsPerInvoke, Description = "4 x Evaluate (force floor)")]
    [ClothWork(4)]
    public void FourEvaluations()
    {
        var state = _cloth.InitialState;
        for (var s = 0; s < 4 * ClothFixture.StepsPerInvoke; s++)
        {
            _cloth.System.Evaluate(0, state, _derivative);
        }
    }

    [Benchmark(OperationsPerInvoke = ClothFixture.StepsPerInvoke, Description = "Math.NET RK4")]
    [ClothWork(4)]
    public MathNetVector MathNet() => _mathNet.Solve(_initial, _cloth.TimeStep, ClothFixture.StepsPerInvoke);

    [Benchmark(OperationsPerInvoke = ClothFixture.StepsPerInvoke, Description = "Student RK4")]
    [ClothWork(4)]
    public void Student()
    {
        _student.Reset();
        for (var s = 0; s < ClothFixture.StepsPerInvoke; s++)
        {
            _student.StepRk4((float)_cloth.TimeStep);
        }
    }
}
