using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Integrators;

/// <summary>
/// Velocity Verlet in the form that stays second order when forces depend on velocity (drag, dampers).
/// </summary>
/// <remarks>
/// a0 = a(t, x, v); x(t + h) = x + v h + a0 h^2 / 2; a1 = a(t + h, x(t + h), v + a0 h);
/// v(t + h) = v + (a0 + a1) h / 2.
/// Derivation: the position is the Taylor expansion to h^2; the velocity is the trapezoidal rule on the
/// acceleration, whose end value needs v(t + h) itself: an Euler predictor v + a0 h supplies it, which keeps the
/// local error O(h^3) (global O(h^2)) even with drag. Without velocity-dependent forces it is the classic,
/// symplectic velocity Verlet. Two force evaluations per step.
/// Stability: an undamped oscillator of angular frequency omega needs h omega &lt; 2.
/// Needs an <see cref="ISecondOrderSystem"/>.
/// </remarks>
public sealed class VelocityVerlet : IIntegrator
{
    private double[]? _a0;
    private double[]? _a1;
    private double[]? _predicted;

    /// <inheritdoc />
    public string Name => "velocity-verlet";

    /// <inheritdoc />
    public int Order => 2;

    /// <inheritdoc />
    public void Step(IOdeSystem system, double time, ReadOnlySpan<double> state, Span<double> next, double dt)
    {
        StepChecks.Check(system, state, next, dt);
        var mechanical = StepChecks.SecondOrder(system, Name);
        var n = mechanical.CoordinateCount;
        var a0 = _a0 = StepChecks.Sized(_a0, n);
        var a1 = _a1 = StepChecks.Sized(_a1, n);
        var predicted = _predicted = StepChecks.Sized(_predicted, n);
        var y = state.ForReading();
        var x = y.Slice(0, n);
        var v = y.Slice(n, n);
        var x1 = next.Slice(0, n);
        var v1 = next.Slice(n, n);

        mechanical.ComputeAccelerations(time, x, v, a0);
        var halfSquare = 0.5 * dt * dt;
        for (var i = 0; i < n; i++)
        {
            x1[i] = x[i] + (dt * v[i]) + (halfSquare * a0[i]);
            predicted[i] = v[i] + (dt * a0[i]);
        }

        mechanical.ComputeAccelerations(time + dt, x1, predicted, a1);
        var half = 0.5 * dt;
        for (var i = 0; i < n; i++)
        {
            v1[i] = v[i] + (half * (a0[i] + a1[i]));
        }
    }
}
