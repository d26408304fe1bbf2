using System;
using System.Collections.Generic;
using System.Runtime.InteropServices;
using BenchmarkDotNet.Attributes;
using ParticlePhysics.Benchmarks.Columns;
using ParticlePhysics.Forces;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// What the core's hot loop could gain, measured rather than guessed: one evaluation of every spring of the cloth
/// (the loop that takes about three quarters of an RK4 step, by perf) by the library's
/// <see cref="SpringNetwork.AddForces"/>, and by two rewrites of the same arithmetic kept here as experiments:
/// <list type="bullet">
/// <item><c>Packed</c> (<see cref="PackedSprings"/>): safe code that netstandard2.1 allows: the springs as one array of structs
/// (ends and k, L, c together: one bounds check per spring) and positions, velocities and forces seen as spans of
/// 3-double structs with <see cref="MemoryMarshal.Cast{TFrom, TTo}(Span{TFrom})"/> (one check per particle access
/// instead of three), the count hoisted out of the loop.</item>
/// <item><c>Unchecked</c>: the same loop as the library over the same flat arrays, through pointers (no bounds
/// checks at all): the ceiling, and what the C reference does.</item>
/// </list>
/// The verify mode checks that both give bit-identical forces to the library's. Not library code.
/// </summary>
[MemoryDiagnoser]
[Config(typeof(ClothColumnsConfig))]
public class SpringKernelBenchmarks
{
    private SpringKernels _kernels = null!;

    [ParamsSource(nameof(Sizes))]
    public int N { get; set; }

    public static IEnumerable<int> Sizes => BenchmarkSizes.Kernel;

    [GlobalSetup]
    public void Setup() => _kernels = new SpringKernels(new ClothFixture(N));

    [Benchmark(Baseline = true, Description = "SpringNetwork.AddForces")]
    [ClothWork(1)]
    public void Library() => _kernels.Library();

    [Benchmark(Description = "Packed (safe, structs)")]
    [ClothWork(1)]
    public void Packed() => _kernels.Packed();

    [Benchmark(Description = "Unchecked (pointers)")]
    [ClothWork(1)]
    public void Unchecked() => _kernels.Unchecked();
}
