using System;
using System.Collections.Generic;
using System.CommandLine;
using System.Globalization;
using System.Linq;
using ParticlePhysics.Constraints;
using ParticlePhysics.Demo.Cli;
using ParticlePhysics.Demo.Running;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Demo.Scenarios;

/// <summary><c>pendulum</c>: a mass on a rod (a hard constraint) to an anchor at the origin, released at rest at an angle.</summary>
internal sealed class PendulumDefinition : ScenarioDefinition
{
    private static readonly PendulumScenario _defaults = new();
    private readonly Option<double> _mass = Options.Number("--mass", "Mass m of the bob", "kg", _defaults.Mass, NumberRule.Mass);
    private readonly Option<double> _length = Options.Number("--length", "Length L of the rod", "m", _defaults.Length, NumberRule.Positive);
    private readonly Option<double> _angle = Options.Number("--angle", "Starting angle theta0 from the downward vertical, between 0 and 180 exclusive", "degrees", _defaults.Angle, NumberRule.Finite);
    private readonly Option<double> _drag = Options.Number("--drag", "Linear drag lambda on the bob (the exact solution needs 0)", "N s/m", _defaults.Drag, NumberRule.NonNegative);
    private readonly Option<double> _gravity = Options.Gravity(_defaults.Gravity);

    public override string Name => "pendulum";

    public override string Description =>
        "A mass on a rod of length L to an anchor at the origin, released at rest at theta0; gravity; the rod a hard "
        + "constraint. Exact: sin(theta / 2) = k sn(K(k) - w t, k), k = sin(theta0 / 2), w = sqrt(g / L), period 4 K(k) / w.";

    public override double DefaultTimeStep => PendulumScenario.DefaultTimeStep;

    public override double DefaultDuration => PendulumScenario.DefaultDuration;

    public override double ConvergenceTimeStep => 0.005;

    public override double ConvergenceDuration => 2;

    public override string ExactSolutionCondition => "without drag (--drag 0)";

    public override IReadOnlyList<Option> PhysicsOptions => new Option[] { _mass, _length, _angle, _drag, _gravity };

    protected override ScenarioSetup Build(ParseResult? parse)
    {
        var angle = Value(parse, _angle);
        if (!(angle > 0 && angle < 180))
        {
            throw new UsageException(string.Format(
                CultureInfo.InvariantCulture, "--angle must be between 0 and 180 degrees, exclusive; got {0:R}.", angle));
        }

        var scenario = new PendulumScenario
        {
            Mass = Value(parse, _mass),
            Length = Value(parse, _length),
            Angle = angle,
            Drag = Value(parse, _drag),
            Gravity = Value(parse, _gravity),
        };
        var exact = scenario.HasExactSolution ? scenario : null;
        var period = scenario.Period;
        var extras = new List<ExtraColumn>
        {
            new("angle", s => PendulumScenario.AngleOf(s.System.GetPosition(0)) * 180 / Math.PI),
        };
        if (exact is not null)
        {
            extras.Add(new ExtraColumn("angle_exact", s => scenario.ExactAngle(s.System.Time).Angle * 180 / Math.PI));
        }

        extras.Add(new ExtraColumn("period", s => ((PeriodObserver)s.Observer!).Period));
        extras.Add(new ExtraColumn("period_exact", _ => period));
        extras.Add(new ExtraColumn("rod_error", s => Rods(s.System).MaxRelativeViolation(s.System.Positions)));
        var table = exact is null
            ? new[] { "t", "x0", "y0", "angle", "period", "rod_error", "energy" }
            : new[] { "t", "x0", "y0", "angle", "angle_exact", "error", "energy" };
        return new ParticleSetup(Name, scenario.Build, 1, exact, extras: extras, observer: () => new PeriodObserver())
        {
            TableColumnList = table,
            SummaryColumnList = new[] { "angle", "period", "period_exact", "rod_error" },
            PlotSeriesList = exact is null
                ? new (string, string?)[] { ("y0", null) }
                : new (string, string?)[] { ("y0", "y0_exact") },
        };
    }

    internal static RodNetwork Rods(ParticleWorld world) => world.Constraints.OfType<RodNetwork>().First();
}
