using System.Collections.Generic;
using System.CommandLine;
using ParticlePhysics.Demo.Cli;
using ParticlePhysics.Demo.Running;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Demo.Scenarios;

/// <summary><c>two-mass-chain</c>: anchor - spring 1 - mass 1 - spring 2 - mass 2, with drag on each mass and gravity.</summary>
internal sealed class TwoMassChainDefinition : ScenarioDefinition
{
    private static readonly TwoMassChainScenario _defaults = new();
    private readonly Option<double> _m1 = Options.Number("--m1", "Mass m1 of particle 1", "kg", _defaults.M1, NumberRule.Mass);
    private readonly Option<double> _m2 = Options.Number("--m2", "Mass m2 of particle 2", "kg", _defaults.M2, NumberRule.Mass);
    private readonly Option<double> _k1 = Options.Number("--k1", "Stiffness k1 of spring 1 (anchor to particle 1)", "N/m", _defaults.K1, NumberRule.NonNegative);
    private readonly Option<double> _k2 = Options.Number("--k2", "Stiffness k2 of spring 2 (particle 1 to particle 2)", "N/m", _defaults.K2, NumberRule.NonNegative);
    private readonly Option<double> _c1 = Options.Number("--c1", "Linear drag c1 on particle 1", "N s/m", _defaults.C1, NumberRule.NonNegative);
    private readonly Option<double> _c2 = Options.Number("--c2", "Linear drag c2 on particle 2", "N s/m", _defaults.C2, NumberRule.NonNegative);
    private readonly Option<double> _restLength1 = Options.Number("--rest-length", "Rest length L1 of spring 1", "m", _defaults.RestLength1, NumberRule.NonNegative);
    private readonly Option<double> _restLength2 = Options.Number("--rest-length2", "Rest length L2 of spring 2", "m", _defaults.RestLength2, NumberRule.NonNegative);
    private readonly Option<double?> _y1 = Options.OptionalNumber("--y1", "Starting height of particle 1 [default: -L1]", "m", NumberRule.Finite);
    private readonly Option<double?> _y2 = Options.OptionalNumber("--y2", "Starting height of particle 2 [default: -L1 - L2]", "m", NumberRule.Finite);
    private readonly Option<double> _gravity = Options.Gravity(_defaults.Gravity);

    public override string Name => "two-mass-chain";

    public override string Description =>
        "The course's chain: anchor - spring 1 (k1, L1) - mass 1 - spring 2 (k2, L2) - mass 2, drag on each mass, "
        + "gravity; exact by a matrix exponential while the chain hangs along the vertical axis.";

    public override double DefaultTimeStep => TwoMassChainScenario.DefaultTimeStep;

    public override double DefaultDuration => TwoMassChainScenario.DefaultDuration;

    public override double ConvergenceTimeStep => 0.01;

    public override double ConvergenceDuration => 5;

    public override IReadOnlyList<Option> PhysicsOptions =>
        new Option[] { _m1, _m2, _k1, _k2, _c1, _c2, _restLength1, _restLength2, _y1, _y2, _gravity };

    protected override ScenarioSetup Build(ParseResult? parse)
    {
        var scenario = new TwoMassChainScenario
        {
            M1 = Value(parse, _m1),
            M2 = Value(parse, _m2),
            K1 = Value(parse, _k1),
            K2 = Value(parse, _k2),
            C1 = Value(parse, _c1),
            C2 = Value(parse, _c2),
            RestLength1 = Value(parse, _restLength1),
            RestLength2 = Value(parse, _restLength2),
            Gravity = Value(parse, _gravity),
        };
        if (Value(parse, _y1) is { } y1)
        {
            scenario.Y1 = y1;
        }

        if (Value(parse, _y2) is { } y2)
        {
            scenario.Y2 = y2;
        }

        return new ParticleSetup(Name, scenario.Build, 2, scenario)
        {
            TableColumnList = new[] { "t", "y0", "y1", "vy0", "vy1", "y0_exact", "y1_exact", "error" },
            SummaryColumnList = new[] { "y0", "y1", "vy0", "vy1" },
            PlotSeriesList = new (string, string?)[] { ("y0", "y0_exact"), ("y1", "y1_exact") },
            Parameters = new[]
            {
                new KeyValuePair<string, object>("y1", scenario.Y1),
                new KeyValuePair<string, object>("y2", scenario.Y2),
            },
        };
    }
}
