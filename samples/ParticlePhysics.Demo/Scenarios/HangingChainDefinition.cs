using System.Collections.Generic;
using System.CommandLine;
using System.Globalization;
using ParticlePhysics.Demo.Cli;
using ParticlePhysics.Demo.Running;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Demo.Scenarios;

/// <summary><c>hanging-chain</c>: N particles joined by rods between two pins, settling into the discrete catenary.</summary>
internal sealed class HangingChainDefinition : ScenarioDefinition
{
    private static readonly HangingChainScenario _defaults = new();
    private readonly Option<int?> _particles = ParticlesOption();
    private readonly Option<double> _length = Options.Number("--length", "Length L of the chain", "m", _defaults.Length, NumberRule.Positive);
    private readonly Option<double> _span = Options.Number("--span", "Span D between the pins, less than L", "m", _defaults.Span, NumberRule.Positive);
    private readonly Option<double> _mass = Options.Number("--mass", "Total mass M, split evenly over the particles", "kg", _defaults.Mass, NumberRule.Mass);
    private readonly Option<double> _drag = Options.Number("--drag", "Linear drag lambda on every particle", "N s/m", _defaults.Drag, NumberRule.NonNegative);
    private readonly Option<double> _gravity = Options.Gravity(_defaults.Gravity);

    public override string Name => "hanging-chain";

    public override string Description =>
        "N particles joined by N - 1 rods of length L / (N - 1), the ends pinned a span D apart, starting in a V; "
        + "gravity and drag. It settles into the discrete catenary: one horizontal tension H, slopes linear in the index.";

    public override double DefaultTimeStep => HangingChainScenario.DefaultTimeStep;

    public override double DefaultDuration => HangingChainScenario.DefaultDuration;

    public override bool HasExactSolution => false;

    public override IReadOnlyList<Option> PhysicsOptions => new Option[] { _particles, _length, _span, _mass, _drag, _gravity };

    protected override ScenarioSetup Build(ParseResult? parse)
    {
        var scenario = new HangingChainScenario
        {
            Particles = parse?.GetValue(_particles) ?? _defaults.Particles,
            Length = Value(parse, _length),
            Span = Value(parse, _span),
            Mass = Value(parse, _mass),
            Drag = Value(parse, _drag),
            Gravity = Value(parse, _gravity),
        };
        if (!(scenario.Span < scenario.Length))
        {
            throw new UsageException(string.Format(
                CultureInfo.InvariantCulture,
                "--span {0:R} must be shorter than the chain's --length {1:R}.",
                scenario.Span,
                scenario.Length));
        }

        var rest = scenario.Gravity > 0 ? scenario.RestShape() : null;
        var middle = scenario.MiddleParticle;
        var y = string.Create(CultureInfo.InvariantCulture, $"y{middle}");
        var vy = string.Create(CultureInfo.InvariantCulture, $"vy{middle}");
        var extras = new[]
        {
            new ExtraColumn("catenary_distance", s => rest?.MaxDistance(s.System.Positions) ?? double.NaN),
            new ExtraColumn("rod_error", s => PendulumDefinition.Rods(s.System).MaxRelativeViolation(s.System.Positions)),
        };
        return new ParticleSetup(Name, scenario.Build, scenario.Particles, exact: null, extras: extras)
        {
            TableColumnList = new[] { "t", y, vy, "catenary_distance", "rod_error", "energy" },
            SummaryColumnList = new[] { y, "catenary_distance", "rod_error" },
            PlotSeriesList = new (string, string?)[] { (y, null) },
            Parameters = new[] { new KeyValuePair<string, object>("particles", (double)scenario.Particles) },
        };
    }

    /// <summary><c>--particles N</c>: odd, 3 to 1001, checked at parse time like every count.</summary>
    private static Option<int?> ParticlesOption() => new("--particles")
    {
        Description = "Number N of particles: odd, 3 to 1001",
        HelpName = "N",
        DefaultValueFactory = _ => _defaults.Particles,
        CustomParser = result =>
        {
            var text = result.Tokens.Count > 0 ? result.Tokens[0].Value : null;
            if (text is null)
            {
                return _defaults.Particles;
            }

            if (!int.TryParse(text, NumberStyles.Integer, CultureInfo.InvariantCulture, out var n)
                || n < HangingChainScenario.MinParticles || n > HangingChainScenario.MaxParticles || n % 2 == 0)
            {
                result.AddError(string.Create(
                    CultureInfo.InvariantCulture,
                    $"--particles must be an odd whole number from {HangingChainScenario.MinParticles} to {HangingChainScenario.MaxParticles}; got '{text}'."));
                return null;
            }

            return n;
        },
    };
}
