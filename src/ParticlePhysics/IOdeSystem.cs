using System;

namespace ParticlePhysics;

/// <summary>
/// A first-order ordinary differential equation dy/dt = f(t, y) of fixed dimension.
/// Every integrator of the library works on this interface, so the course's scalar example
/// dy/dt = -2 y t is solved by the same code as a cloth of thousands of particles.
/// </summary>
public interface IOdeSystem
{
    /// <summary>The number of components of the state vector y.</summary>
    int Dimension { get; }

    /// <summary>
    /// Writes f(t, y) into <paramref name="derivative"/>, a buffer the caller owns.
    /// Must not allocate, must not keep the spans, and must not modify anything that changes later evaluations.
    /// </summary>
    /// <param name="time">The time t.</param>
    /// <param name="state">The state y, of length <see cref="Dimension"/>.</param>
    /// <param name="derivative">Receives dy/dt, of length <see cref="Dimension"/>.</param>
    void Evaluate(double time, ReadOnlySpan<double> state, Span<double> derivative);
}
