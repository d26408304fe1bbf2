using System;
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
    public const double DefaultFriction = 0.5;
    public const double DefaultRollingFriction = 0.1;

    public string Name => "granular";

    public SceneObject Read(ObjectReader reader, SceneReadContext context)
    {
        var block = LatticeBlock.Read(reader, "granular", "grain");
        var spacing = block.Spacing;
        var radius = reader.Number("radius", spacing / 2, ValueRule.Positive, "m");
        if (radius > spacing / 2)
        {
            throw reader.Error(reader.Get("radius")!.Value, reader.PathOf("radius"), FormattableString.Invariant($"must be at most half the spacing ({spacing / 2:G6} m): neighbouring grains would start inside each other"));
        }

        return new GranularObject(block.Positions, radius, block.Mass)
        {
            Friction = reader.Number("friction", DefaultFriction, ValueRule.NonNegative, string.Empty),
            RollingFriction = reader.Number("rollingFriction", DefaultRollingFriction, ValueRule.NonNegative, string.Empty),
        };
    }

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
