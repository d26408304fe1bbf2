using System.Collections.Generic;
using ParticlePhysics.Cloth;
using ParticlePhysics.Scenes.Kinds;

namespace ParticlePhysics.Scenes.Objects;

/// <summary>
/// <c>rope</c>: a rope along <c>points</c> [[x, y, z], ...] (its particles, in order; at least two, consecutive points
/// apart) (<see cref="RopeBuilder"/>). <c>velocities</c> (per point), <c>mass</c> (total, kg, default 1, lumped by
/// segment length), <c>stretch</c> {"stiffness": k, "damping": c} (a spring on every segment) or
/// {"inextensible": true} (a rod on every segment, the default), <c>bending</c> {"rigidity": EI} (N m^2),
/// <c>pinned</c> (point indices), <c>radius</c> (m, each).
/// </summary>
internal sealed class RopeKind : ISceneObjectKind
{
    public string Name => "rope";

    public SceneObject Read(ObjectReader reader, SceneReadContext context)
    {
        var points = reader.Vectors("points", "m") ?? throw reader.ObjectError("a rope object needs \"points\": [[x, y, z], ...] in m, at least two");
        if (points.Count < 2)
        {
            throw reader.Error(reader.Get("points")!.Value, reader.PathOf("points"), "lists fewer than two points; a rope needs at least two");
        }

        var positions = new Vector3d[points.Count];
        for (var i = 0; i < positions.Length; i++)
        {
            positions[i] = points[i].Vector;
            if (i > 0 && !((positions[i] - positions[i - 1]).Length > 0))
            {
                throw reader.Error(points[i].Where, ObjectReader.Index(reader.PathOf("points"), i), $"is where point {i - 1} is; a segment needs a length");
            }
        }

        var builder = new RopeBuilder(positions)
        {
            TotalMass = reader.Number("mass", 1.0, ValueRule.Mass, "kg"),
            Radius = reader.Number("radius", 0.0, ValueRule.NonNegative, "m"),
            Stretch = RopeStretch.Inextensible,
        };
        if (reader.Object("stretch", "a rope's stretch") is { } stretch)
        {
            if (stretch.Has("stiffness"))
            {
                if (stretch.Has("inextensible"))
                {
                    throw stretch.ObjectError("give {\"stiffness\": k} (springs) or {\"inextensible\": true} (rods), not both");
                }

                builder.Stretch = RopeStretch.Springs;
                builder.SpringStiffness = stretch.Number("stiffness", null, ValueRule.NonNegative, "N/m");
                builder.SpringDamping = stretch.Number("damping", 0.0, ValueRule.NonNegative, "N s/m");
            }
            else if (!stretch.Boolean("inextensible", true))
            {
                throw stretch.Error(stretch.Get("inextensible")!.Value, stretch.PathOf("inextensible"), "false would leave the rope no stretch at all; give {\"stiffness\": k} for springs");
            }

            stretch.Finish();
        }

        if (reader.Object("bending", "a rope's bending") is { } bending)
        {
            builder.BendingRigidity = bending.Number("rigidity", null, ValueRule.NonNegative, "N m^2");
            bending.Finish();
        }

        var velocities = reader.Vectors("velocities", "m/s");
        if (velocities is not null && velocities.Count != points.Count)
        {
            throw reader.Error(reader.Get("velocities")!.Value, reader.PathOf("velocities"), $"lists {velocities.Count} velocities for {points.Count} points; give one per point");
        }

        foreach (var pin in reader.Indices("pinned") ?? new List<IndexRef>())
        {
            if (pin.Value >= points.Count)
            {
                throw reader.Error(pin.Where, pin.Path, $"names no point of this rope: pinned takes its own indices, 0 to {points.Count - 1}");
            }

            builder.Pin(pin.Value);
        }

        foreach (var m in builder.ParticleMasses())
        {
            if (!(m > 0) || double.IsInfinity(1.0 / m))
            {
                throw reader.ObjectError("its mass spread over its points leaves one with a mass whose inverse is not finite; give it more mass");
            }
        }

        var v = new Vector3d[velocities?.Count ?? 0];
        for (var i = 0; i < v.Length; i++)
        {
            v[i] = velocities![i].Vector;
        }

        return new RopeObject(builder, v);
    }

    private sealed class RopeObject : SceneObject
    {
        private readonly RopeBuilder _builder;
        private readonly Vector3d[] _velocities;
        private int _first;

        public RopeObject(RopeBuilder builder, Vector3d[] velocities)
        {
            _builder = builder;
            _velocities = velocities;
        }

        public override int ParticleCount => _builder.PointCount;

        public override void AddParticles(SceneBuilder builder) => _first = _builder.AddParticles(builder.World, _velocities);

        public override void AddElements(SceneBuilder builder)
        {
            var springs = _builder.Stretch == RopeStretch.Springs ? builder.Springs : null;
            var rods = _builder.Stretch == RopeStretch.Inextensible ? builder.Rods : null;
            var bending = _builder.BendingRigidity > 0 ? builder.Bending : null;
            var elements = bending?.Count ?? 0;
            _builder.AddElements(_first, springs, rods, bending);
            builder.Count(springs is null ? "rods" : "springs", _builder.PointCount - 1);
            builder.Count("bending elements", (bending?.Count ?? 0) - elements);
        }
    }
}
