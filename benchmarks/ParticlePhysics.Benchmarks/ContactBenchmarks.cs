using System;
using System.Collections.Generic;
using System.Linq;
using BenchmarkDotNet.Attributes;
using ParticlePhysics.Contacts;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// Issue 11: the contact stage alone (<see cref="ContactSet.Resolve"/>), for 1,000, 10,000 and 100,000 particles in a box
/// (<see cref="ParticleBoxScenario"/>: three layers, landed and resting after 100 steps of 1 ms), on one step of gravity
/// from that state. Target: the cost per particle flat within 1.5x from 1,000 to 100,000 (the broad phase and every
/// stage are O(N)), and no allocation.
/// </summary>
[MemoryDiagnoser]
[Config(typeof(ContactColumnsConfig))]
public class ContactBenchmarks
{
    private const double Dt = 0.001;
    private ContactSet _contacts = null!;
    private ParticleWorld _world = null!;
    private double[] _start = Array.Empty<double>();
    private double[] _end = Array.Empty<double>();
    private double[] _work = Array.Empty<double>();

    [ParamsSource(nameof(Counts))]
    public int Particles { get; set; }

    public static IEnumerable<int> Counts => BenchmarkSizes.Quick ? new[] { 1000 } : new[] { 1000, 10_000, 100_000 };

    [GlobalSetup]
    public void Setup()
    {
        _world = new ParticleBoxScenario { Count = Particles }.Build();
        _contacts = _world.Constraints.OfType<ContactSet>().Single();
        var rk4 = new RungeKutta4();
        for (var s = 0; s < 100; s++)
        {
            _world.Step(rk4, Dt);
        }

        // The integrator's end of one more step under gravity alone (what RK4 computes exactly): x + v dt - g dt^2 / 2.
        var n = _world.Count;
        _start = _world.State.ToArray();
        _end = (double[])_start.Clone();
        for (var i = 0; i < n; i++)
        {
            var y = (3 * i) + 1;
            _end[y] += (_start[(3 * n) + y] * Dt) - (0.5 * 9.81 * Dt * Dt);
            _end[(3 * n) + y] -= 9.81 * Dt;
        }

        _work = (double[])_end.Clone();
        Resolve(); // sizes the buffers
    }

    [Benchmark(Description = "Contact stage, one step")]
    public int Resolve()
    {
        // Restore the integrator's end (a copy of 6 N doubles, small beside the stage), then correct it.
        _end.CopyTo(_work, 0);
        var n = _world.Count;
        var start = _start.AsSpan();
        var work = _work.AsSpan();
        var context = new ConstraintContext(
            0, Dt, start.Slice(0, 3 * n), start.Slice(3 * n), work.Slice(0, 3 * n), work.Slice(3 * n),
            _world.Masses, _world.InverseMasses, _world.Radii);
        _contacts.Resolve(in context);
        return _contacts.ImpactCount;
    }
}
