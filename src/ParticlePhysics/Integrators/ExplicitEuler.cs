using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Integrators;

/// <summary>
/// Explicit (forward) Euler, the course's scheme: the slope at the start of the step is held over the whole step.
/// </summary>
/// <remarks>
/// y(t + h) = y(t) + h f(t, y(t)); for a particle, v(t + h) = v + a(t) h and x(t + h) = x + v(t) h.
/// Derivation: integrate dy/dt = f over [t, t + h] with f frozen at its value at t; the error per step is
/// h^2 y''/2, so the global error is O(h) (order 1).
/// Stability: on y' = lambda y it multiplies by (1 + h lambda); it needs |1 + h lambda| &lt;= 1, so an undamped
/// oscillator (lambda = +-i omega) gains energy at every step for any h, and decay needs h &lt; 2 / |lambda|.
/// </remarks>
public sealed class ExplicitEuler : IIntegrator
{
    private double[]? _slope;

    /// <inheritdoc />
    public string Name => "explicit-euler";

    /// <inheritdoc />
    public int Order => 1;

    /// <inheritdoc />
    public void Step(IOdeSystem system, double time, ReadOnlySpan<double> state, Span<double> next, double dt)
    {
        var y = state.ForReading();
        StepChecks.Check(system, state, next, dt);
        var slope = _slope = StepChecks.Sized(_slope, state.Length);
        system.Evaluate(time, state, slope);
        for (var i = 0; i < state.Length; i++)
        {
            next[i] = y[i] + (dt * slope[i]);
        }
    }
}
