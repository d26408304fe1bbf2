using System.Collections.Generic;
using System.CommandLine;
using ParticlePhysics.Demo.Cli;
using ParticlePhysics.Demo.Running;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Demo.Scenarios;

/// <summary><c>free-fall</c>: one particle released at rest at height h, under gravity and linear drag.</summary>
internal sealed class FreeFallDefinition : ScenarioDefinition
{
    private static readonly FreeFallScenario _defaults = new();
    private readonly Option<double> _mass = Options.Number("--mass", "Mass m of the particle", "kg", _defaults.Mass, NumberRule.Mass);
    private readonly Option<double> _drag = Options.Number("--drag", "Linear drag lambda (force -lambda v)", "N s/m", _defaults.Drag, NumberRule.NonNegative);
    private readonly Option<double> _height = Options.Number("--height", "Starting height h", "m", _defaults.Height, NumberRule.Finite);
    private readonly Option<double> _gravity = Options.Gravity(_defaults.Gravity);

    public override string Name => "free-fall";

    public override string Description =>
        "The course's free fall with viscous friction: one particle at rest at (0, h, 0), gravity and linear drag; "
        + "exact y(t) = h - g tau t + g tau^2 (1 - e^(-t/tau)), tau = m / lambda.";

    public override double DefaultTimeStep => FreeFallScenario.DefaultTimeStep;

    public override double DefaultDuration => FreeFallScenario.DefaultDuration;

    public override double ConvergenceTimeStep => 0.1;

    public override double ConvergenceDuration => 2;

    public override IReadOnlyList<Option> PhysicsOptions => new Option[] { _mass, _drag, _height, _gravity };

    protected override ScenarioSetup Build(ParseResult? parse)
    {
        var scenario = new FreeFallScenario
        {
            Mass = Value(parse, _mass),
            Drag = Value(parse, _drag),
            Height = Value(parse, _height),
            Gravity = Value(parse, _gravity),
        };
        return new ParticleSetup(Name, scenario.Build, 1, scenario)
        {
            TableColumnList = new[] { "t", "y0", "vy0", "y0_exact", "vy0_exact", "error" },
            SummaryColumnList = new[] { "y0", "vy0" },
            PlotSeriesList = new (string, string?)[] { ("y0", "y0_exact") },
        };
    }
}
