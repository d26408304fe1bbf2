using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Integrators;

/// <summary>
/// Semi-implicit (symplectic) Euler: the velocity first, then the position with the new velocity, as the course's
/// FreeFall script does.
/// </summary>
/// <remarks>
/// v(t + h) = v + h a(t, x, v); x(t + h) = x + h v(t + h).
/// Derivation: explicit Euler on v, implicit Euler on x. The map is symplectic, so on a conservative system it
/// conserves a modified energy within O(h): the energy of an undamped oscillator stays bounded forever instead of
/// growing. Global error O(h) (order 1). Stability: an oscillator of angular frequency omega needs h omega &lt; 2.
/// Needs an <see cref="ISecondOrderSystem"/>. A kick and a drift (<see cref="IKickDriftIntegrator"/>): rods then close
/// each step as SHAKE does, so that their energy stays bounded too.
/// </remarks>
public sealed class SemiImplicitEuler : IKickDriftIntegrator
{
    private double[]? _acceleration;

    /// <inheritdoc />
    public string Name => "semi-implicit-euler";

    /// <inheritdoc />
    public int Order => 1;

    /// <inheritdoc />
    public void Step(IOdeSystem system, double time, ReadOnlySpan<double> state, Span<double> next, double dt)
    {
        StepChecks.Check(system, state, next, dt);
        var mechanical = StepChecks.SecondOrder(system, Name);
        var n = mechanical.CoordinateCount;
        var a = _acceleration = StepChecks.Sized(_acceleration, n);
        var y = state.ForReading();
        var x = y.Slice(0, n);
        var v = y.Slice(n, n);
        mechanical.ComputeAccelerations(time, x, v, a);
        for (var i = 0; i < n; i++)
        {
            var v1 = v[i] + (dt * a[i]);
            next[n + i] = v1;
            next[i] = x[i] + (dt * v1);
        }
    }
}
