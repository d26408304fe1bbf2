using System.Collections.Generic;
using System.CommandLine;
using ParticlePhysics.Demo.Cli;
using ParticlePhysics.Demo.Running;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Demo.Scenarios;

/// <summary><c>mass-spring-damper</c>: one mass on a zero-rest-length spring to an anchor at the origin, with drag and gravity.</summary>
internal sealed class MassSpringDamperDefinition : ScenarioDefinition
{
    private static readonly MassSpringDamperScenario _defaults = new();
    private readonly Option<double> _mass = Options.Number("--mass", "Mass m", "kg", _defaults.Mass, NumberRule.Mass);
    private readonly Option<double> _stiffness = Options.Number("--stiffness", "Spring stiffness k", "N/m", _defaults.Stiffness, NumberRule.NonNegative);
    private readonly Option<double> _damping = Options.Number("--damping", "Linear drag c on the mass", "N s/m", _defaults.Damping, NumberRule.NonNegative);
    private readonly Option<double> _y0 = Options.Number("--y0", "Starting height y0", "m", _defaults.Y0, NumberRule.Finite);
    private readonly Option<double> _v0 = Options.Number("--v0", "Starting vertical velocity v0", "m/s", _defaults.V0, NumberRule.Finite);
    private readonly Option<double> _gravity = Options.Gravity(_defaults.Gravity);

    public override string Name => "mass-spring-damper";

    public override string Description =>
        "One mass on a spring to a fixed anchor, with linear drag and gravity: m y'' + c y' + k y = -m g, "
        + "equilibrium y = -m g / k; exact for under-, critically and over-damped motion.";

    public override double DefaultTimeStep => MassSpringDamperScenario.DefaultTimeStep;

    public override double DefaultDuration => MassSpringDamperScenario.DefaultDuration;

    public override double ConvergenceTimeStep => 0.025;

    public override double ConvergenceDuration => 10;

    public override IReadOnlyList<Option> PhysicsOptions => new Option[] { _mass, _stiffness, _damping, _y0, _v0, _gravity };

    protected override ScenarioSetup Build(ParseResult? parse)
    {
        var scenario = new MassSpringDamperScenario
        {
            Mass = Value(parse, _mass),
            Stiffness = Value(parse, _stiffness),
            Damping = Value(parse, _damping),
            Y0 = Value(parse, _y0),
            V0 = Value(parse, _v0),
            Gravity = Value(parse, _gravity),
        };
        return new ParticleSetup(Name, scenario.Build, 1, scenario)
        {
            TableColumnList = new[] { "t", "y0", "vy0", "y0_exact", "vy0_exact", "error", "energy" },
            SummaryColumnList = new[] { "y0", "vy0" },
            PlotSeriesList = new (string, string?)[] { ("y0", "y0_exact") },
        };
    }
}
