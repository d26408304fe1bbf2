using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Scenarios;

/// <summary>
/// The course's RK4 example, a scalar ODE whose right-hand side depends on time: dy/dt = -2 y t, y(0) = 1,
/// with the exact solution y = e^(-t^2).
/// </summary>
public sealed class GaussianDecayOde : IOdeSystem, IExactSolution
{
    /// <summary>The contract's default time step, in seconds.</summary>
    public const double DefaultTimeStep = 0.1;

    /// <summary>The contract's default duration, in seconds.</summary>
    public const double DefaultDuration = 2;

    /// <summary>One component, y.</summary>
    public int Dimension => 1;

    /// <summary>The initial state, y(0) = 1.</summary>
    public static double InitialValue => 1.0;

    /// <inheritdoc />
    public void Evaluate(double time, ReadOnlySpan<double> state, Span<double> derivative) =>
        derivative[0] = -2.0 * state.ForReading()[0] * time;

    /// <inheritdoc />
    public void ExactState(double time, Span<double> state) => state[0] = Math.Exp(-time * time);
}
