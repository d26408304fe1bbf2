using System;
using System.Collections.Generic;
using System.Runtime.InteropServices;
using ParticlePhysics.Forces;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// An experiment for the core, not library code: the cloth's <see cref="SpringNetwork"/> rewritten as suggested in
/// docs/benchmarks.md (springs as an array of structs, particle buffers viewed as spans of 3-double structs, the
/// count hoisted), with the same arithmetic in the same order, so that a cloth stepped with it stays bit-identical to
/// the library's (the verify mode checks it). <see cref="Replace"/> swaps it into a system in place of its network.
/// </summary>
internal sealed class PackedSprings : IForceGenerator
{
    private readonly Spring[] _springs;

    private PackedSprings(Spring[] springs)
    {
        _springs = springs;
    }

    /// <summary>
    /// Replaces the cloth's spring network by a packed copy, keeping the generators' order (so the force sums, and the
    /// results, are bit-identical). Every spring of a <see cref="Scenarios.ClothScenario"/> has the same k and c.
    /// </summary>
    public static void Replace(ParticleWorld system, double stiffness, double damping)
    {
        var generators = new List<IForceGenerator>(system.Forces);
        foreach (var generator in generators)
        {
            system.RemoveForce(generator);
        }

        foreach (var generator in generators)
        {
            if (generator is SpringNetwork network)
            {
                if (network.AnchoredCount != 0)
                {
                    throw new ArgumentException("The experiment handles particle-particle springs only.", nameof(system));
                }

                system.AddForce(From(network, stiffness, damping));
            }
            else
            {
                system.AddForce(generator);
            }
        }
    }

    /// <summary>A packed copy of the particle-particle springs of <paramref name="network"/>, all of stiffness k and damping c.</summary>
    public static PackedSprings From(SpringNetwork network, double stiffness, double damping)
    {
        var springs = new Spring[network.Count];
        for (var s = 0; s < springs.Length; s++)
        {
            var (first, second) = network.GetEnds(s);
            springs[s] = new Spring(first, second, stiffness, network.GetRestLength(s), damping);
        }

        return new PackedSprings(springs);
    }

    public void AddForces(in ParticleState state, Span<double> forces)
    {
        var x = MemoryMarshal.Cast<double, Triple>(state.Positions);
        var v = MemoryMarshal.Cast<double, Triple>(state.Velocities);
        var f = MemoryMarshal.Cast<double, Triple>(forces);
        var springs = _springs;
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

    [StructLayout(LayoutKind.Sequential)]
    private struct Triple
    {
        public double X;
        public double Y;
        public double Z;
    }

    private readonly struct Spring
    {
        public Spring(int first, int second, double stiffness, double restLength, double damping)
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
