using System;

namespace ParticlePhysics;

/// <summary>
/// A time-stepping scheme: advances the state y of an <see cref="IOdeSystem"/> from t to t + dt.
/// It reads <c>state</c> and writes <c>next</c> (two distinct buffers), so a caller can check the result before
/// committing it. Integrators own their scratch buffers: they allocate on the first step of a given dimension and
/// never again. The time loop, output and error handling live outside, in <see cref="ParticleWorld.Step"/> or
/// <see cref="OdeSimulation.Step"/>.
/// </summary>
public interface IIntegrator
{
    /// <summary>The integrator's name as the demo's <c>--integrator</c> takes it, such as <c>rk4</c>.</summary>
    string Name { get; }

    /// <summary>The order of accuracy: the global error shrinks as dt to this power.</summary>
    int Order { get; }

    /// <summary>Advances <paramref name="state"/> at <paramref name="time"/> by <paramref name="dt"/> into <paramref name="next"/>.</summary>
    /// <param name="system">The system; some integrators need an <see cref="ISecondOrderSystem"/>.</param>
    /// <param name="time">The time t of <paramref name="state"/>.</param>
    /// <param name="state">y(t), of length <see cref="IOdeSystem.Dimension"/>.</param>
    /// <param name="next">Receives y(t + dt); must not overlap <paramref name="state"/>.</param>
    /// <param name="dt">The time step, a positive finite number of seconds.</param>
    void Step(IOdeSystem system, double time, ReadOnlySpan<double> state, Span<double> next, double dt);
}
