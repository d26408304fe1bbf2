using System;

namespace ParticlePhysics.Demo.Running;

/// <summary>A plain ODE's <see cref="OdeSimulation"/> seen as an <see cref="ISimulation"/>.</summary>
internal sealed class OdeSimulationAdapter : ISimulation
{
    private readonly OdeSimulation _simulation;

    public OdeSimulationAdapter(OdeSimulation simulation)
    {
        _simulation = simulation;
    }

    public ReadOnlySpan<double> State => _simulation.State;

    public void Step(IIntegrator integrator, double dt) => _simulation.Step(integrator, dt);
}
