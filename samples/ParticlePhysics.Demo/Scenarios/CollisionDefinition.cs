using System.Collections.Generic;
using System.CommandLine;
using System.Globalization;
using ParticlePhysics.Demo.Cli;
using ParticlePhysics.Demo.Running;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Demo.Scenarios;

/// <summary><c>collision</c>: two particles of radius r meet head-on.</summary>
internal sealed class CollisionDefinition : ScenarioDefinition
{
    private static readonly CollisionScenario _defaults = new();
    private readonly Option<double> _m1 = Options.Number("--m1", "Mass of particle 0, starting at (-1, 0, 0)", "kg", _defaults.Mass1, NumberRule.Mass);
    private readonly Option<double> _m2 = Options.Number("--m2", "Mass of particle 1, starting at (1, 0, 0)", "kg", _defaults.Mass2, NumberRule.Mass);
    private readonly Option<double> _v1 = Options.Number("--v1", "Velocity of particle 0 along x", "m/s", _defaults.Velocity1, NumberRule.Finite);
    private readonly Option<double> _v2 = Options.Number("--v2", "Velocity of particle 1 along x", "m/s", _defaults.Velocity2, NumberRule.Finite);
    private readonly Option<double> _radius = Options.Number("--radius", "Radius r of both (less than 1)", "m", _defaults.Radius, NumberRule.NonNegative);
    private readonly Option<double> _restitution = Options.Number("--restitution", "Restitution e, 0 to 1", string.Empty, _defaults.Restitution, NumberRule.Fraction);
    private readonly Option<double> _gravity = Options.Gravity(_defaults.Gravity);

    public override string Name => "collision";

    /// <inheritdoc />
    public override string? ConvergenceRefusal =>
        "the particles move along straight lines and meet at the exact time of their impact under every integrator: the "
        + "error is round-off (about 1e-14) and has no order in dt";

    public override string Description =>
        "Two particles of radius r meet head-on; exact: they touch at t* = (2 - 2 r) / (v1 - v2) and leave with "
        + "v1' = (m1 v1 + m2 v2 - m2 e (v1 - v2)) / (m1 + m2), v2' = (m1 v1 + m2 v2 + m1 e (v1 - v2)) / (m1 + m2). No gravity unless --gravity.";

    public override double DefaultTimeStep => CollisionScenario.DefaultTimeStep;

    public override double DefaultDuration => CollisionScenario.DefaultDuration;

    public override IReadOnlyList<Option> PhysicsOptions => new Option[] { _m1, _m2, _v1, _v2, _radius, _restitution, _gravity };

    protected override ScenarioSetup Build(ParseResult? parse)
    {
        var scenario = new CollisionScenario
        {
            Mass1 = Value(parse, _m1),
            Mass2 = Value(parse, _m2),
            Velocity1 = Value(parse, _v1),
            Velocity2 = Value(parse, _v2),
            Radius = Value(parse, _radius),
            Restitution = Value(parse, _restitution),
            Gravity = Value(parse, _gravity),
        };
        if (!(scenario.Radius < 1))
        {
            throw new UsageException(string.Format(
                CultureInfo.InvariantCulture,
                "--radius {0:R} must be less than 1: the particles start 2 m apart and would overlap.",
                scenario.Radius));
        }

        return new CollisionSetup(Name, scenario)
        {
            TableColumnList = new[] { "t", "x0", "vx0", "x1", "vx1", "x0_exact", "x1_exact", "error" },
            SummaryColumnList = new[] { "x0", "vx0", "x1", "vx1" },
            PlotSeriesList = new (string, string?)[] { ("x0", "x0_exact"), ("x1", "x1_exact") },
        };
    }
}
