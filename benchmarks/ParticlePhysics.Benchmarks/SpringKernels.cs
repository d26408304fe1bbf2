using System;
using System.Runtime.InteropServices;
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
    private readonly PackedSpring[] _packed;

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
        _packed = new PackedSpring[count];
        for (var s = 0; s < count; s++)
        {
            (_first[s], _second[s]) = _network.GetEnds(s);
            _parameters[3 * s] = cloth.Scenario.Stiffness;
            _parameters[(3 * s) + 1] = _network.GetRestLength(s);
            _parameters[(3 * s) + 2] = cloth.Scenario.Damping;
            _packed[s] = new PackedSpring(
                _first[s], _second[s], _parameters[3 * s], _parameters[(3 * s) + 1], _parameters[(3 * s) + 2]);
        }
    }

    public ReadOnlySpan<double> Forces => _forces;

    public void Library()
    {
        Array.Clear(_forces);
        var view = new ParticleState(0, _positions, _velocities, _masses, _inverseMasses);
        _network.AddForces(in view, _forces);
    }

    public void Packed()
    {
        Array.Clear(_forces);
        var x = MemoryMarshal.Cast<double, Triple>(_positions.AsSpan());
        var v = MemoryMarshal.Cast<double, Triple>(_velocities.AsSpan());
        var f = MemoryMarshal.Cast<double, Triple>(_forces.AsSpan());
        var springs = _packed;
        for (var s = 0; s < springs.Length; s++)
        {
            ref readonly var spring = ref springs[s];
            ref readonly var xa = ref x[spring.First];
            ref readonly var xb = ref x[spring.Second];
            double dx = xa.X - xb.X, dy = xa.Y - xb.Y, dz = xa.Z - xb.Z;
            var lengthSquared = (dx * dx) + (dy * dy) + (dz * dz);
            if (lengthSquared == 0.0)
            {
                continue;
            }

            var length = Math.Sqrt(lengthSquared);
            var inverse = 1.0 / length;
            double ux = dx * inverse, uy = dy * inverse, uz = dz * inverse;
            ref readonly var va = ref v[spring.First];
            ref readonly var vb = ref v[spring.Second];
            var closing = ((va.X - vb.X) * ux) + ((va.Y - vb.Y) * uy) + ((va.Z - vb.Z) * uz);
            var magnitude = (spring.Stiffness * (length - spring.RestLength)) + (spring.Damping * closing);
            double fx = magnitude * ux, fy = magnitude * uy, fz = magnitude * uz;
            ref var fa = ref f[spring.First];
            fa.X -= fx;
            fa.Y -= fy;
            fa.Z -= fz;
            ref var fb = ref f[spring.Second];
            fb.X += fx;
            fb.Y += fy;
            fb.Z += fz;
        }
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

    private static SpringNetwork FindNetwork(ParticleSystem system)
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

    /// <summary>Three doubles: a particle's position, velocity or force, as a view of the flat buffers.</summary>
    [StructLayout(LayoutKind.Sequential)]
    private struct Triple
    {
        public double X;
        public double Y;
        public double Z;
    }

    /// <summary>A spring with its ends and parameters together: 40 bytes, one bounds check per spring.</summary>
    private readonly struct PackedSpring
    {
        public PackedSpring(int first, int second, double stiffness, double restLength, double damping)
        {
            First = first;
            Second = second;
            Stiffness = stiffness;
            RestLength = restLength;
            Damping = damping;
        }

        public int First { get; }

        public int Second { get; }

        public double Stiffness { get; }

        public double RestLength { get; }

        public double Damping { get; }
    }
}
