using System;
using ParticlePhysics.Forces;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The spring loop of <see cref="SpringNetwork.AddForces"/>, and two rewrites of the same arithmetic in the same
/// order (so the forces are bit-identical), for <see cref="SpringKernelBenchmarks"/>. The state is a cloth a few
/// steps after rest, so that every spring is stretched and moving.
/// </summary>
internal sealed class SpringKernels
{
    private readonly SpringNetwork _network;
    private readonly double[] _positions;
    private readonly double[] _velocities;
    private readonly double[] _masses;
    private readonly double[] _inverseMasses;
    private readonly double[] _forces;
    private readonly int[] _first;
    private readonly int[] _second;
    private readonly double[] _parameters;
    private readonly PackedSprings _packed;

    public SpringKernels(ClothFixture cloth)
    {
        var system = cloth.System;
        var rk4 = new Integrators.RungeKutta4();
        for (var s = 0; s < 8; s++)
        {
            system.Step(rk4, cloth.TimeStep);
        }

        _network = FindNetwork(system);
        _positions = system.Positions.ToArray();
        _velocities = system.Velocities.ToArray();
        _masses = system.Masses.ToArray();
        _inverseMasses = system.InverseMasses.ToArray();
        _forces = new double[_positions.Length];
        var count = _network.Count;
        _first = new int[count];
        _second = new int[count];
        _parameters = new double[3 * count];
        _packed = PackedSprings.From(_network, cloth.Scenario.Stiffness, cloth.Scenario.Damping);
        for (var s = 0; s < count; s++)
        {
            (_first[s], _second[s]) = _network.GetEnds(s);
            _parameters[3 * s] = cloth.Scenario.Stiffness;
            _parameters[(3 * s) + 1] = _network.GetRestLength(s);
            _parameters[(3 * s) + 2] = cloth.Scenario.Damping;
        }
    }

    public ReadOnlySpan<double> Forces => _forces;

    public void Library()
    {
        Array.Clear(_forces);
        var view = new ParticleState(0, _positions, _velocities, _masses, _inverseMasses);
        _network.AddForces(in view, _forces);
    }

    /// <summary>The safe rewrite: <see cref="PackedSprings"/>, the loop suggested for the core.</summary>
    public void Packed()
    {
        Array.Clear(_forces);
        var view = new ParticleState(0, _positions, _velocities, _masses, _inverseMasses);
        _packed.AddForces(in view, _forces);
    }

    public unsafe void Unchecked()
    {
        Array.Clear(_forces);
        var count = _first.Length;
        fixed (double* x = _positions, v = _velocities, forces = _forces, p = _parameters)
        fixed (int* first = _first, second = _second)
        {
            for (var s = 0; s < count; s++)
            {
                int a = 3 * first[s], b = 3 * second[s], q = 3 * s;
                double dx = x[a] - x[b], dy = x[a + 1] - x[b + 1], dz = x[a + 2] - x[b + 2];
                var lengthSquared = (dx * dx) + (dy * dy) + (dz * dz);
                if (lengthSquared == 0.0)
                {
                    continue;
                }

                var length = Math.Sqrt(lengthSquared);
                var inverse = 1.0 / length;
                double ux = dx * inverse, uy = dy * inverse, uz = dz * inverse;
                var closing = ((v[a] - v[b]) * ux) + ((v[a + 1] - v[b + 1]) * uy) + ((v[a + 2] - v[b + 2]) * uz);
                var magnitude = (p[q] * (length - p[q + 1])) + (p[q + 2] * closing);
                double fx = magnitude * ux, fy = magnitude * uy, fz = magnitude * uz;
                forces[a] -= fx;
                forces[a + 1] -= fy;
                forces[a + 2] -= fz;
                forces[b] += fx;
                forces[b + 1] += fy;
                forces[b + 2] += fz;
            }
        }
    }

    private static SpringNetwork FindNetwork(ParticleWorld system)
    {
        foreach (var generator in system.Forces)
        {
            if (generator is SpringNetwork network)
            {
                return network;
            }
        }

        throw new InvalidOperationException("The cloth has no SpringNetwork.");
    }
}
