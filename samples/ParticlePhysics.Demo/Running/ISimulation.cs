using System;

namespace ParticlePhysics.Demo.Running;

/// <summary>
/// What the runner steps: a particle system or a plain ODE, seen through its state vector, which is laid out as
/// the scenario's exact solution lays out its own (for particles: [positions | velocities]).
/// </summary>
internal interface ISimulation
{
    /// <summary>The committed state vector.</summary>
    ReadOnlySpan<double> State { get; }

    /// <summary>Advances one step; throws <see cref="SimulationDivergedException"/> and keeps the last good state on failure.</summary>
    void Step(IIntegrator integrator, double dt);
}
