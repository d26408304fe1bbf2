using System;

namespace ParticlePhysics;

/// <summary>
/// An <see cref="IOdeSystem"/> that is a mechanical system x'' = a(t, x, v): its state vector is
/// [x (n values) | v (n values)] with dx/dt = v. Integrators that treat positions and velocities differently
/// (semi-implicit Euler, velocity Verlet) need this form.
/// </summary>
public interface ISecondOrderSystem : IOdeSystem
{
    /// <summary>The number n of position coordinates; <see cref="IOdeSystem.Dimension"/> is 2 n.</summary>
    int CoordinateCount { get; }

    /// <summary>Writes the accelerations a(t, x, v) into <paramref name="accelerations"/> (length n).</summary>
    /// <param name="time">The time t.</param>
    /// <param name="positions">The positions x, length n.</param>
    /// <param name="velocities">The velocities v, length n.</param>
    /// <param name="accelerations">Receives the accelerations, length n.</param>
    void ComputeAccelerations(
        double time, ReadOnlySpan<double> positions, ReadOnlySpan<double> velocities, Span<double> accelerations);
}
