using System;

namespace ParticlePhysics.Demo.Running;

/// <summary>A <see cref="ParticleWorld"/> seen as an <see cref="ISimulation"/>, with what watches its steps.</summary>
internal sealed class ParticleSimulation : ISimulation
{
    public ParticleSimulation(ParticleWorld system, IStepObserver? observer = null)
    {
        System = system;
        Observer = observer;
    }

    /// <summary>What watches every step of this run (a pendulum's period), or null.</summary>
    public IStepObserver? Observer { get; }

    /// <summary>The particles, for the row layout (positions, velocities, energy).</summary>
    public ParticleWorld System { get; }

    public ReadOnlySpan<double> State => System.State;

    public void Step(IIntegrator integrator, double dt)
    {
        System.Step(integrator, dt);
        Observer?.AfterStep(System);
    }
}
