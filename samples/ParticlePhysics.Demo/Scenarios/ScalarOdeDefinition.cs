using System;
using System.Collections.Generic;
using System.CommandLine;
using ParticlePhysics.Demo.Running;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Demo.Scenarios;

/// <summary><c>scalar-ode</c>: the course's RK4 example dy/dt = -2 y t, y(0) = 1, exact y = e^(-t^2).</summary>
internal sealed class ScalarOdeDefinition : ScenarioDefinition
{
    public override string Name => "scalar-ode";

    public override string Description =>
        "The course's RK4 example, dy/dt = -2 y t, y(0) = 1, exact y = e^(-t^2); columns t,y,exact,error. "
        + "A plain first-order ODE: the integrators that need positions and velocities do not apply.";

    public override double DefaultTimeStep => GaussianDecayOde.DefaultTimeStep;

    public override double DefaultDuration => GaussianDecayOde.DefaultDuration;

    public override bool IsPlainOde => true;

    public override double ConvergenceTimeStep => 0.05;

    public override IReadOnlyList<Option> PhysicsOptions => Array.Empty<Option>();

    protected override ScenarioSetup Build(ParseResult? parse) => new ScalarOdeSetup(new GaussianDecayOde());
}
