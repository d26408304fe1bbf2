using System;

namespace ParticlePhysics.Demo.Running;

/// <summary>A <see cref="ParticleWorld"/> seen as an <see cref="ISimulation"/>.</summary>
internal sealed class ParticleSimulation : ISimulation
{
    public ParticleSimulation(ParticleWorld system)
    {
        System = system;
    }

    /// <summary>The particles, for the row layout (positions, velocities, energy).</summary>
    public ParticleWorld System { get; }

    public ReadOnlySpan<double> State => System.State;

    public void Step(IIntegrator integrator, double dt) => System.Step(integrator, dt);
}
