using System;
using ParticlePhysics.Bodies;
using ParticlePhysics.Constraints;
using ParticlePhysics.Fluids;
using ParticlePhysics.Scenes.Kinds;

namespace ParticlePhysics.Scenes.Objects;

/// <summary>
/// <c>fluid</c>: a block of liquid held at its rest density by position-based fluids (<see cref="PositionBasedFluid"/>).
/// <c>box</c> {"min", "max"} is filled as a rigid box is, cell centres at min + (i + 1/2) h, x fastest, at
/// <c>spacing</c> h; each particle has mass <c>density</c> h^3 (the rest density, kg/m^3, default 1000) and radius
/// h / 2. <c>viscosity</c> is XSPH's c in [0, 1] (default 0), <c>vorticity</c> the confinement epsilon (default 0).
/// <c>cohesion</c> is accepted only as 0 until surface tension is built, so that a scene asking for it is not run
/// without it.
/// </summary>
internal sealed class FluidKind : ISceneObjectKind
{
    public const double DefaultDensity = 1000.0;

    public string Name => "fluid";

    public SceneObject Read(ObjectReader reader, SceneReadContext context)
    {
        var box = reader.Object("box", "a fluid's box")
            ?? throw reader.ObjectError("a fluid object needs \"box\": {\"min\": [x, y, z], \"max\": [x, y, z]} in m, the block its particles fill");
        var min = box.Vector("min", null, "m");
        var max = box.Vector("max", null, "m");
        if (!(max.X > min.X && max.Y > min.Y && max.Z > min.Z))
        {
            throw box.Error(box.Get("max")!.Value, box.PathOf("max"), FormattableString.Invariant($"must be above \"min\" {Show(min)} along every axis: the block the fluid fills"));
        }

        box.Finish();
        var spacing = reader.Number("spacing", null, ValueRule.Positive, "m");
        var count = CountOf(max.X - min.X, spacing) * CountOf(max.Y - min.Y, spacing) * CountOf(max.Z - min.Z, spacing);
        if (count > ParticleWorld.MaxParticles)
        {
            throw reader.ObjectError(FormattableString.Invariant($"fills with {count:N0} particles; a scene holds at most {ParticleWorld.MaxParticles:N0}"));
        }

        var density = reader.Number("density", DefaultDensity, ValueRule.Positive, "kg/m^3");
        var mass = density * spacing * spacing * spacing;
        if (!(mass > 0) || double.IsInfinity(mass) || double.IsInfinity(1.0 / mass))
        {
            throw reader.Error(reader.Get("density")!.Value, reader.PathOf("density"), FormattableString.Invariant($"gives each particle a mass {mass:G6} kg (density h^3) whose inverse is not finite"));
        }

        var viscosity = reader.Number("viscosity", 0.0, ValueRule.NonNegative, string.Empty);
        if (viscosity > 1.0)
        {
            throw reader.Error(reader.Get("viscosity")!.Value, reader.PathOf("viscosity"), "must be in [0, 1]: XSPH's c, the fraction of the way to the neighbours' mean velocity per 1/60 s");
        }

        var vorticity = reader.Number("vorticity", 0.0, ValueRule.NonNegative, string.Empty);
        var cohesion = reader.Number("cohesion", 0.0, ValueRule.NonNegative, string.Empty);
        if (cohesion != 0.0)
        {
            throw reader.Error(reader.Get("cohesion")!.Value, reader.PathOf("cohesion"), "must be 0: cohesion and surface tension are not built yet (issue \"fluids\")");
        }

        var positions = BodyLattice.Box(0.5 * (min + max), max - min, Rotation3d.Identity, spacing);
        return new FluidObject(positions, new SceneBuilder.FluidParameters(spacing, density, viscosity, vorticity));
    }

    // The box rule's count along one side (BodyLattice.Box): round(side / h), at least 1; counted before filling so
    // that a block too fine for a scene is refused before its array is made.
    private static double CountOf(double side, double spacing) => Math.Max(1.0, Math.Round(side / spacing));

    private static string Show(Vector3d v) => FormattableString.Invariant($"[{v.X:G6}, {v.Y:G6}, {v.Z:G6}]");

    private sealed class FluidObject : SceneObject
    {
        private readonly Vector3d[] _positions;
        private readonly SceneBuilder.FluidParameters _fluid;
        private int _first;

        public FluidObject(Vector3d[] positions, SceneBuilder.FluidParameters fluid)
        {
            _positions = positions;
            _fluid = fluid;
        }

        public override int ParticleCount => _positions.Length;

        public override void AddParticles(SceneBuilder builder)
            => _first = builder.AddSpheres(_positions, _fluid.Density * _fluid.Spacing * _fluid.Spacing * _fluid.Spacing, 0.5 * _fluid.Spacing);

        public override void AddElements(SceneBuilder builder)
        {
            builder.AddFluid(_fluid, _first, _positions.Length);
            builder.Count("fluid particles", _positions.Length);
        }
    }
}
