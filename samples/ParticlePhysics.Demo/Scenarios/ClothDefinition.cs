using System;
using System.Collections.Generic;
using System.CommandLine;
using System.Globalization;
using ParticlePhysics.Cloth;
using ParticlePhysics.Demo.Cli;
using ParticlePhysics.Demo.Running;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Demo.Scenarios;

/// <summary><c>cloth</c>: a square of n x n particles joined by structural, shear and bend springs, held by two corners.</summary>
internal sealed class ClothDefinition : ScenarioDefinition
{
    private static readonly ClothScenario _defaults = new();
    private readonly Option<double> _size = Options.Number("--size", "Side S of the square", "m", _defaults.Size, NumberRule.Positive);
    private readonly Option<double> _resolution = Options.Number("--resolution", "Spacing r between neighbours; S / r must be a whole number", "m", _defaults.Resolution, NumberRule.Positive);
    private readonly Option<double> _mass = Options.Number("--mass", "Total mass M, split evenly over the particles", "kg", _defaults.Mass, NumberRule.Mass);
    private readonly Option<double> _stiffness = Options.Number("--stiffness", "Stiffness k of every spring", "N/m", _defaults.Stiffness, NumberRule.NonNegative);
    private readonly Option<double> _damping = Options.Number("--damping", "Axial damping c of every spring", "N s/m", _defaults.Damping, NumberRule.NonNegative);
    private readonly Option<double> _drag = Options.Number("--drag", "Linear drag lambda on every particle", "N s/m", _defaults.Drag, NumberRule.NonNegative);
    private readonly Option<double> _gravity = Options.Gravity(_defaults.Gravity);
    private readonly Option<string> _pin = Options.Choice("--pin", "Pinned particles: the two corners of row 0, all of row 0, or none", "corners", "corners", "edge", "none");

    public override string Name => "cloth";

    public override string Description =>
        "A square cloth of n x n particles (n = S / r + 1) lying flat in y = 0, joined by structural, shear and bend "
        + "springs, with drag and gravity, held by two corners. No exact solution.";

    public override double DefaultTimeStep => ClothScenario.DefaultTimeStep;

    public override double DefaultDuration => ClothScenario.DefaultDuration;

    public override bool HasExactSolution => false;

    public override IReadOnlyList<Option> PhysicsOptions =>
        new Option[] { _size, _resolution, _mass, _stiffness, _damping, _drag, _gravity, _pin };

    protected override ScenarioSetup Build(ParseResult? parse)
    {
        var scenario = new ClothScenario
        {
            Size = Value(parse, _size),
            Resolution = Value(parse, _resolution),
            Mass = Value(parse, _mass),
            Stiffness = Value(parse, _stiffness),
            Damping = Value(parse, _damping),
            Drag = Value(parse, _drag),
            Gravity = Value(parse, _gravity),
            Pinning = Value(parse, _pin) switch
            {
                "edge" => ClothPinning.Edge,
                "none" => ClothPinning.None,
                _ => ClothPinning.Corners,
            },
        };
        var n = ParticlesPerSide(scenario);
        var particleMass = scenario.Mass / ((double)n * n);
        if (!double.IsFinite(1 / particleMass))
        {
            throw new UsageException(string.Format(
                CultureInfo.InvariantCulture,
                "--mass {0:R} split over {1} particles gives {2:R} kg each, too small for 1/m to be finite (at least 5.6e-309 kg each).",
                scenario.Mass,
                n * n,
                particleMass));
        }

        return new ClothSetup(Name, scenario.Build, n)
        {
            TableColumnList = new[] { "t", "min_y", "max_speed", "energy" },
            SummaryColumnList = new[] { "min_y", "max_speed", "energy" },
        };
    }

    /// <summary>n = S / r + 1, or a usage error naming --size and --resolution.</summary>
    internal static int ParticlesPerSide(ClothScenario scenario)
    {
        try
        {
            return scenario.ParticlesPerSide;
        }
        catch (ArgumentException exception)
        {
            var ratio = scenario.Size / scenario.Resolution;
            var whole = Math.Abs(ratio - Math.Round(ratio)) <= 1e-9 && ratio >= 1;
            throw new UsageException(
                whole
                    ? string.Format(
                        CultureInfo.InvariantCulture,
                        "--size {0:R} / --resolution {1:R} gives {2:R} particles per side; at most {3} are allowed.",
                        scenario.Size,
                        scenario.Resolution,
                        Math.Round(ratio) + 1,
                        ClothScenario.MaxParticlesPerSide)
                    : string.Format(
                        CultureInfo.InvariantCulture,
                        "--resolution {0:R} does not divide --size {1:R}: size / resolution = {2:R} must be a whole number >= 1.",
                        scenario.Resolution,
                        scenario.Size,
                        ratio),
                exception);
        }
    }
}
