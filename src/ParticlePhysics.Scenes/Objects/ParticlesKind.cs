using System.Collections.Generic;
using ParticlePhysics.Scenes.Kinds;

namespace ParticlePhysics.Scenes.Objects;

/// <summary>
/// <c>particles</c>: <c>positions</c> (required), <c>velocities</c> (default rest), <c>mass</c> (each, default 1) or
/// <c>masses</c>, <c>radius</c> (each, default 0) or <c>radii</c>, <c>pinned</c> (local indices; a pinned particle
/// keeps its velocity). Particles in list order.
/// </summary>
internal sealed class ParticlesKind : ISceneObjectKind
{
    public string Name => "particles";

    public SceneObject Read(ObjectReader reader, SceneReadContext context)
    {
        var positions = reader.Vectors("positions", "m") ?? throw reader.ObjectError("a particles object needs \"positions\": [[x, y, z], ...] in m");
        var count = positions.Count;
        if (count == 0)
        {
            throw reader.Error(reader.Get("positions")!.Value, reader.PathOf("positions"), "lists no particle; give at least one [x, y, z]");
        }

        var velocities = reader.Vectors("velocities", "m/s");
        if (velocities is not null && velocities.Count != count)
        {
            throw reader.Error(reader.Get("velocities")!.Value, reader.PathOf("velocities"), $"lists {velocities.Count} velocities for {count} positions; give one per particle");
        }

        var masses = PerParticle(reader, "mass", "masses", 1.0, ValueRule.Mass, "kg", count);
        var radii = PerParticle(reader, "radius", "radii", 0.0, ValueRule.NonNegative, "m", count);
        var pinned = reader.Indices("pinned");
        var pins = new bool[count];
        if (pinned is not null)
        {
            foreach (var pin in pinned)
            {
                if (pin.Value >= count)
                {
                    throw reader.Error(pin.Where, pin.Path, $"names no particle of this object: pinned takes its own indices, 0 to {count - 1}");
                }

                pins[pin.Value] = true;
            }
        }

        var particles = new ParticlesObject(count);
        for (var i = 0; i < count; i++)
        {
            particles.Positions[i] = positions[i].Vector;
            particles.Velocities[i] = velocities?[i].Vector ?? Vector3d.Zero;
            particles.Masses[i] = masses[i];
            particles.Radii[i] = radii[i];
        }

        particles.Pinned = pins;
        return particles;
    }

    // "mass" for all or "masses" for each, never both.
    private static double[] PerParticle(ObjectReader reader, string one, string each, double defaultValue, ValueRule rule, string unit, int count)
    {
        var values = new double[count];
        var list = reader.Numbers(each, rule, unit);
        if (list is not null)
        {
            if (reader.Has(one))
            {
                throw reader.Error(reader.Get(one)!.Value, reader.PathOf(one), $"give \"{one}\" (the same for every particle) or \"{each}\" (one per particle), not both", showValue: false);
            }

            if (list.Count != count)
            {
                throw reader.Error(reader.Get(each)!.Value, reader.PathOf(each), $"lists {list.Count} values for {count} particles; give one per particle");
            }

            list.CopyTo(values);
            return values;
        }

        var value = reader.Number(one, defaultValue, rule, unit);
        for (var i = 0; i < count; i++)
        {
            values[i] = value;
        }

        return values;
    }

    private sealed class ParticlesObject : SceneObject
    {
        public ParticlesObject(int count)
        {
            Positions = new Vector3d[count];
            Velocities = new Vector3d[count];
            Masses = new double[count];
            Radii = new double[count];
            Pinned = new bool[count];
        }

        public Vector3d[] Positions { get; }

        public Vector3d[] Velocities { get; }

        public double[] Masses { get; }

        public double[] Radii { get; }

        public bool[] Pinned { get; set; }

        public override int ParticleCount => Positions.Length;

        public override void AddParticles(SceneBuilder builder)
        {
            var world = builder.World;
            for (var i = 0; i < Positions.Length; i++)
            {
                var index = world.AddParticle(Positions[i], Velocities[i], Masses[i]);
                if (Radii[i] > 0)
                {
                    world.SetRadius(index, Radii[i]);
                }

                if (Pinned[i])
                {
                    world.Pin(index, Velocities[i]);
                }
            }
        }
    }
}
