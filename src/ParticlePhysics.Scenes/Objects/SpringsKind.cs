using System.Collections.Generic;
using ParticlePhysics.Scenes.Kinds;

namespace ParticlePhysics.Scenes.Objects;

/// <summary>
/// <c>springs</c>: <c>pairs</c> [[i, j], ...] of global particle indices, <c>stiffness</c> k (N/m), <c>damping</c> c
/// (N s/m, along the spring's axis, default 0), <c>restLength</c> (one for all) or <c>restLengths</c> (one per pair),
/// default the distance at the start. The force is the contract's: with d = x_i - x_j, l = |d|, u = d / l,
/// F_i = -(k (l - L) + c (v_i - v_j) . u) u, and for a rest length of 0 the zero-rest-length spring
/// F_i = -k (x_i - x_j), linear and exact at l = 0 (with its damping along the axis when c &gt; 0). Under xpbd each is
/// a distance constraint of compliance 1 / k.
/// </summary>
internal sealed class SpringsKind : ISceneObjectKind
{
    public string Name => "springs";

    public SceneObject Read(ObjectReader reader, SceneReadContext context)
    {
        var pairs = reader.Pairs("pairs") ?? throw reader.ObjectError("a springs object needs \"pairs\": [[i, j], ...] of particle indices");
        var stiffness = reader.Number("stiffness", null, ValueRule.NonNegative, "N/m");
        var damping = reader.Number("damping", 0.0, ValueRule.NonNegative, "N s/m");
        var restLengths = RestLengths(reader, "restLength", "restLengths", pairs.Count, ValueRule.NonNegative);
        return new SpringsObject(pairs, stiffness, damping, restLengths);
    }

    /// <summary>
    /// One length per pair from "restLength" (for all) or "restLengths" (each), never both; null when neither is
    /// given (the distance at the start, known once the particles are built).
    /// </summary>
    internal static double[]? RestLengths(ObjectReader reader, string one, string each, int count, ValueRule rule)
    {
        var list = reader.Numbers(each, rule, "m");
        if (list is not null)
        {
            if (reader.Has(one))
            {
                throw reader.Error(reader.Get(one)!.Value, reader.PathOf(one), $"give \"{one}\" (the same for every pair) or \"{each}\" (one per pair), not both", showValue: false);
            }

            if (list.Count != count)
            {
                throw reader.Error(reader.Get(each)!.Value, reader.PathOf(each), $"lists {list.Count} lengths for {count} pairs; give one per pair");
            }

            return list.ToArray();
        }

        if (!reader.Has(one))
        {
            return null;
        }

        var value = reader.Number(one, null, rule, "m");
        var all = new double[count];
        for (var i = 0; i < count; i++)
        {
            all[i] = value;
        }

        return all;
    }

    /// <summary>The distance between the pair's particles as built: a rest length left out. Refuses one that is not finite.</summary>
    internal static double StartDistance(SceneBuilder builder, (IndexRef First, IndexRef Second) pair, string file)
    {
        var d = (builder.World.GetPosition(pair.First.Value) - builder.World.GetPosition(pair.Second.Value)).Length;
        if (double.IsInfinity(d) || double.IsNaN(d))
        {
            throw new SceneException(file, pair.First.Path.Substring(0, pair.First.Path.Length - 3), pair.First.Where.Line, pair.First.Where.Column, string.Empty,
                "the particles are too far apart at the start for a length to be finite; give the length");
        }

        return d;
    }

    private sealed class SpringsObject : SceneObject
    {
        private readonly List<(IndexRef First, IndexRef Second)> _pairs;
        private readonly double _stiffness;
        private readonly double _damping;
        private readonly double[]? _restLengths;

        public SpringsObject(List<(IndexRef, IndexRef)> pairs, double stiffness, double damping, double[]? restLengths)
        {
            _pairs = pairs;
            _stiffness = stiffness;
            _damping = damping;
            _restLengths = restLengths;
        }

        public override void CheckIndices(SceneIndexCheck check)
        {
            foreach (var (first, second) in _pairs)
            {
                check.Particle(first);
                check.Particle(second);
            }
        }

        public override void AddElements(SceneBuilder builder)
        {
            builder.Count("springs", _pairs.Count);
            for (var s = 0; s < _pairs.Count; s++)
            {
                var (first, second) = _pairs[s];
                var rest = _restLengths?[s] ?? StartDistance(builder, _pairs[s], builder.File);
                if (rest > 0)
                {
                    builder.Springs.Add(first.Value, second.Value, _stiffness, rest, _damping);
                    continue;
                }

                // The contract's zero-rest-length spring, linear in the positions; its damping, if any, along the axis.
                builder.LinearSprings.Add(first.Value, second.Value, _stiffness);
                if (_damping > 0)
                {
                    builder.Springs.Add(first.Value, second.Value, 0.0, 0.0, _damping);
                }
            }
        }
    }
}
