using System;
using System.Collections.Generic;
using System.CommandLine;
using System.Globalization;
using ParticlePhysics.Cloth;
using ParticlePhysics.Demo.Cli;
using ParticlePhysics.Demo.Running;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Demo.Scenarios;

/// <summary><c>drape</c>: the cloth, unpinned by default, falls onto a sphere with friction.</summary>
internal sealed class DrapeDefinition : ScenarioDefinition
{
    private static readonly DrapeScenario _defaults = new();
    private readonly Option<double> _size = Options.Number("--size", "Side S of the square", "m", _defaults.Cloth.Size, NumberRule.Positive);
    private readonly Option<double> _resolution = Options.Number("--resolution", "Spacing r between neighbours; S / r must be a whole number", "m", _defaults.Cloth.Resolution, NumberRule.Positive);
    private readonly Option<double> _mass = Options.Number("--mass", "Total mass M, split evenly over the particles", "kg", _defaults.Cloth.Mass, NumberRule.Mass);
    private readonly Option<double> _stiffness = Options.Number("--stiffness", "Stiffness k of every spring", "N/m", _defaults.Cloth.Stiffness, NumberRule.NonNegative);
    private readonly Option<double> _damping = Options.Number("--damping", "Axial damping c of every spring", "N s/m", _defaults.Cloth.Damping, NumberRule.NonNegative);
    private readonly Option<double> _drag = Options.Number("--drag", "Linear drag lambda on every particle", "N s/m", _defaults.Cloth.Drag, NumberRule.NonNegative);
    private readonly Option<double> _gravity = Options.Gravity(_defaults.Cloth.Gravity);
    private readonly Option<string> _pin = Options.Choice("--pin", "Pinned particles: the two corners of row 0, all of row 0, or none", "none", "corners", "edge", "none");
    private readonly Option<double> _radius = Options.Number("--radius", "Radius of every particle", "m", _defaults.Radius, NumberRule.NonNegative);
    private readonly Option<double> _sphereRadius = Options.Number("--sphere-radius", "Radius of the sphere", "m", _defaults.SphereRadius, NumberRule.Positive);
    private readonly Option<double> _sphereY = Options.Number("--sphere-y", "Height of the sphere's centre, at (S/2, y, S/2)", "m", _defaults.SphereY, NumberRule.Finite);
    private readonly Option<double> _friction = Options.Number("--friction", "Coulomb friction mu of the sphere (its restitution is 0)", string.Empty, _defaults.Friction, NumberRule.NonNegative);

    public override string Name => "drape";

    public override string Description =>
        "The cloth scenario's cloth, pinned nowhere by default, of particle spheres of radius r, falling from y = 0 onto a "
        + "sphere with friction; it collides with itself too. No exact solution: no particle enters the sphere.";

    public override double DefaultTimeStep => DrapeScenario.DefaultTimeStep;

    public override double DefaultDuration => DrapeScenario.DefaultDuration;

    public override bool HasExactSolution => false;

    public override IReadOnlyList<Option> PhysicsOptions => new Option[]
    {
        _size, _resolution, _mass, _stiffness, _damping, _drag, _gravity, _pin, _radius, _sphereRadius, _sphereY, _friction,
    };

    protected override ScenarioSetup Build(ParseResult? parse)
    {
        var scenario = new DrapeScenario
        {
            Radius = Value(parse, _radius),
            SphereRadius = Value(parse, _sphereRadius),
            SphereY = Value(parse, _sphereY),
            Friction = Value(parse, _friction),
        };
        var cloth = scenario.Cloth;
        cloth.Size = Value(parse, _size);
        cloth.Resolution = Value(parse, _resolution);
        cloth.Mass = Value(parse, _mass);
        cloth.Stiffness = Value(parse, _stiffness);
        cloth.Damping = Value(parse, _damping);
        cloth.Drag = Value(parse, _drag);
        cloth.Gravity = Value(parse, _gravity);
        cloth.Pinning = Value(parse, _pin) switch
        {
            "edge" => ClothPinning.Edge,
            "corners" => ClothPinning.Corners,
            _ => ClothPinning.None,
        };
        var n = ClothDefinition.ParticlesPerSide(cloth);
        var particleMass = cloth.Mass / ((double)n * n);
        if (!double.IsFinite(1 / particleMass))
        {
            throw new UsageException(string.Format(
                CultureInfo.InvariantCulture,
                "--mass {0:R} split over {1} particles gives {2:R} kg each, too small for 1/m to be finite (at least 5.6e-309 kg each).",
                cloth.Mass,
                n * n,
                particleMass));
        }

        // The cloth starts flat at y = 0 over the sphere's centre: within R + r of it, its middle starts inside the sphere.
        if (Math.Abs(scenario.SphereY) < scenario.SphereRadius + scenario.Radius)
        {
            throw new UsageException(string.Format(
                CultureInfo.InvariantCulture,
                "--sphere-y {0:R} puts the sphere of --sphere-radius {1:R} within reach of the cloth at y = 0 (particles of --radius {2:R}): "
                + "the cloth would start inside it; |sphere-y| must be at least {3:R}.",
                scenario.SphereY,
                scenario.SphereRadius,
                scenario.Radius,
                scenario.SphereRadius + scenario.Radius));
        }

        return new DrapeSetup(Name, scenario, n)
        {
            TableColumnList = new[] { "t", "min_y", "max_speed", "sphere_gap", "middle_y", "energy" },
            SummaryColumnList = new[] { "min_y", "max_speed", "sphere_gap", "middle_y" },
        };
    }
}
