using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Integrators;

/// <summary>
/// The classical fourth-order Runge-Kutta method, with the forces evaluated again at each of the four stages
/// (not the course script's shortcut that freezes the acceleration, which is only first order).
/// </summary>
/// <remarks>
/// k1 = f(t, y); k2 = f(t + h/2, y + h k1 / 2); k3 = f(t + h/2, y + h k2 / 2); k4 = f(t + h, y + h k3);
/// y(t + h) = y + h (k1 + 2 k2 + 2 k3 + k4) / 6.
/// Derivation: Simpson's rule on [t, t + h] with the midpoint slope estimated twice; it matches the Taylor series
/// of y to h^4, so the error per step is O(h^5) and the global error O(h^4).
/// Stability: on y' = lambda y the factor is 1 + z + z^2/2 + z^3/6 + z^4/24 (z = h lambda); it needs
/// |z| &lt;= 2.78 on the real axis and h omega &lt;= 2.83 for an oscillator. Four evaluations per step.
/// </remarks>
public sealed class RungeKutta4 : IIntegrator
{
    private double[]? _k;
    private double[]? _stage;

    /// <inheritdoc />
    public string Name => "rk4";

    /// <inheritdoc />
    public int Order => 4;

    /// <inheritdoc />
    public void Step(IOdeSystem system, double time, ReadOnlySpan<double> state, Span<double> next, double dt)
    {
        StepChecks.Check(system, state, next, dt);
        var n = state.Length;
        var k = _k = StepChecks.Sized(_k, n);
        var stage = _stage = StepChecks.Sized(_stage, n);
        var half = 0.5 * dt;
        var sixth = dt / 6.0;
        var third = 2.0 * sixth;

        // The four stages, each followed by one pass over y: next accumulates y + h (k1 + 2 k2 + 2 k3 + k4) / 6
        // while stage takes the next stage's state.
        system.Evaluate(time, state, k);
        VectorKernels.Stage(next, stage, state, k, sixth, half, first: true);
        system.Evaluate(time + half, stage, k);
        VectorKernels.Stage(next, stage, state, k, third, half, first: false);
        system.Evaluate(time + half, stage, k);
        VectorKernels.Stage(next, stage, state, k, third, dt, first: false);
        system.Evaluate(time + dt, stage, k);
        VectorKernels.AddScaled(next, k, sixth);
    }
}
