using System;
using ParticlePhysics.Bodies;
using ParticlePhysics.Constraints;
using ParticlePhysics.Contacts;
using ParticlePhysics.Scenes.Kinds;

namespace ParticlePhysics.Scenes.Objects;

/// <summary>
/// <c>granular</c>: a block of grains (<see cref="ContactSet.SetGranular"/>), solid spheres that spin, with static,
/// dynamic and rolling friction. <c>box</c> {"min", "max"} is filled as a rigid box is, cell centres at
/// min + (i + 1/2) h, x fastest, at <c>spacing</c> h; each grain has mass <c>density</c> h^3 (kg/m^3, default 1000),
/// <c>radius</c> (m, default h / 2, at most h / 2 so that none starts inside another), <c>friction</c> (static and
/// dynamic, default 0.5, met with the other side's by their mean) and <c>rollingFriction</c> (default 0.1).
/// </summary>
internal sealed class GranularKind : ISceneObjectKind
{
    public const double DefaultDensity = 1000.0;
    public const double DefaultFriction = 0.5;
    public const double DefaultRollingFriction = 0.1;

    public string Name => "granular";

    public SceneObject Read(ObjectReader reader, SceneReadContext context)
    {
        var box = reader.Object("box", "a granular block's box")
            ?? throw reader.ObjectError("a granular object needs \"box\": {\"min\": [x, y, z], \"max\": [x, y, z]} in m, the block its grains fill");
        var min = box.Vector("min", null, "m");
        var max = box.Vector("max", null, "m");
        if (!(max.X > min.X && max.Y > min.Y && max.Z > min.Z))
        {
            throw box.Error(box.Get("max")!.Value, box.PathOf("max"), FormattableString.Invariant($"must be above \"min\" {Show(min)} along every axis: the block's far corner"));
        }

        box.Finish();
        var spacing = reader.Number("spacing", null, ValueRule.Positive, "m");
        var count = CountOf(max.X - min.X, spacing) * CountOf(max.Y - min.Y, spacing) * CountOf(max.Z - min.Z, spacing);
        if (count > ParticleWorld.MaxParticles)
        {
            throw reader.ObjectError(FormattableString.Invariant($"fills with {count:N0} grains; a scene holds at most {ParticleWorld.MaxParticles:N0}"));
        }

        var positions = BodyLattice.Box(0.5 * (min + max), max - min, Rotation3d.Identity, spacing);
        var density = reader.Number("density", DefaultDensity, ValueRule.Positive, "kg/m^3");
        var mass = density * spacing * spacing * spacing;
        if (!(mass > 0) || double.IsInfinity(mass) || double.IsInfinity(1.0 / mass))
        {
            throw reader.Error(reader.Get("density")!.Value, reader.PathOf("density"), FormattableString.Invariant($"gives each grain a mass {mass:G6} kg (density h^3) whose inverse is not finite"));
        }

        var radius = reader.Number("radius", spacing / 2, ValueRule.Positive, "m");
        if (radius > spacing / 2)
        {
            throw reader.Error(reader.Get("radius")!.Value, reader.PathOf("radius"), FormattableString.Invariant($"must be at most half the spacing ({spacing / 2:G6} m): neighbouring grains would start inside each other"));
        }

        return new GranularObject(positions, radius, mass)
        {
            Friction = reader.Number("friction", DefaultFriction, ValueRule.NonNegative, string.Empty),
            RollingFriction = reader.Number("rollingFriction", DefaultRollingFriction, ValueRule.NonNegative, string.Empty),
        };
    }

    // The box rule's count along one side (BodyLattice.Box): round(side / h), at least 1; counted before filling so
    // that a block too fine for a scene is refused before its array is made.
    private static double CountOf(double side, double spacing) => Math.Max(1.0, Math.Round(side / spacing));

    private static string Show(Vector3d v) => FormattableString.Invariant($"[{v.X:G6}, {v.Y:G6}, {v.Z:G6}]");

    private sealed class GranularObject : SceneObject
    {
        private readonly Vector3d[] _positions;
        private readonly double _radius;
        private readonly double _mass;
        private int _first;

        public GranularObject(Vector3d[] positions, double radius, double mass)
        {
            _positions = positions;
            _radius = radius;
            _mass = mass;
        }

        public double Friction { get; set; }

        public double RollingFriction { get; set; }

        public override int ParticleCount => _positions.Length;

        public override void AddParticles(SceneBuilder builder) => _first = builder.AddSpheres(_positions, _mass, _radius);

        public override void AddElements(SceneBuilder builder)
        {
            builder.AddGranular(_first, _positions.Length, Friction, RollingFriction);
            builder.Count("grains", _positions.Length);
        }
    }
}
