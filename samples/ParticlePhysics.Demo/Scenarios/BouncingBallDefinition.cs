using System.Collections.Generic;
using System.CommandLine;
using System.Globalization;
using ParticlePhysics.Demo.Cli;
using ParticlePhysics.Demo.Running;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Demo.Scenarios;

/// <summary><c>bouncing-ball</c>: a ball dropped on the ground plane y = 0, with restitution and friction.</summary>
internal sealed class BouncingBallDefinition : ScenarioDefinition
{
    private static readonly BouncingBallScenario _defaults = new();
    private readonly Option<double> _mass = Options.Number("--mass", "Mass m of the ball", "kg", _defaults.Mass, NumberRule.Mass);
    private readonly Option<double> _radius = Options.Number("--radius", "Radius R of the ball", "m", _defaults.Radius, NumberRule.NonNegative);
    private readonly Option<double> _height = Options.Number("--height", "Starting height h of its centre (at least R)", "m", _defaults.Height, NumberRule.Finite);
    private readonly Option<double> _vx0 = Options.Number("--vx0", "Starting horizontal velocity", "m/s", _defaults.Vx0, NumberRule.Finite);
    private readonly Option<double> _restitution = Options.Number("--restitution", "Restitution e of the ground, 0 to 1", string.Empty, _defaults.Restitution, NumberRule.Fraction);
    private readonly Option<double> _friction = Options.Number("--friction", "Coulomb friction mu of the ground", string.Empty, _defaults.Friction, NumberRule.NonNegative);
    private readonly Option<double> _drag = Options.Number("--drag", "Linear drag lambda (no exact solution unless 0)", "N s/m", _defaults.Drag, NumberRule.NonNegative);
    private readonly Option<double> _gravity = Options.Gravity(_defaults.Gravity);

    public override string Name => "bouncing-ball";

    /// <inheritdoc />
    public override string? ConvergenceRefusal =>
        "between impacts the ball flies on parabolas, which rk4, velocity Verlet and rk45 follow exactly, the impacts are "
        + "resolved at their exact times, and from t = 4.06 s it rests: the error is round-off and has no order in dt";

    public override string Description =>
        "A ball of radius R dropped from (0, h, 0) onto the ground y = 0 with restitution e and friction mu; exact apexes "
        + "R + e^(2n) (h - R), bounces ending at T = t1 (1 + e) / (1 - e), then rest at y = R.";

    public override double DefaultTimeStep => BouncingBallScenario.DefaultTimeStep;

    public override double DefaultDuration => BouncingBallScenario.DefaultDuration;

    public override IReadOnlyList<Option> PhysicsOptions =>
        new Option[] { _mass, _radius, _height, _vx0, _restitution, _friction, _drag, _gravity };

    protected override ScenarioSetup Build(ParseResult? parse)
    {
        var scenario = new BouncingBallScenario
        {
            Mass = Value(parse, _mass),
            Radius = Value(parse, _radius),
            Height = Value(parse, _height),
            Vx0 = Value(parse, _vx0),
            Restitution = Value(parse, _restitution),
            Friction = Value(parse, _friction),
            Drag = Value(parse, _drag),
            Gravity = Value(parse, _gravity),
        };
        if (scenario.Height < scenario.Radius)
        {
            throw new UsageException(string.Format(
                CultureInfo.InvariantCulture,
                "--height {0:R} is below --radius {1:R}: the ball would start inside the ground; the height must be at least the radius.",
                scenario.Height,
                scenario.Radius));
        }

        return new BouncingBallSetup(Name, scenario)
        {
            TableColumnList = scenario.HasExactSolution
                ? new[] { "t", "y0", "vy0", "x0", "vx0", "y0_exact", "error" }
                : new[] { "t", "y0", "vy0", "x0", "vx0" },
            SummaryColumnList = new[] { "y0", "vy0", "x0", "vx0" },
            PlotSeriesList = new (string, string?)[] { ("y0", scenario.HasExactSolution ? "y0_exact" : null) },
        };
    }
}
