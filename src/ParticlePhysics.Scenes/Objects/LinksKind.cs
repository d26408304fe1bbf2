using System.Collections.Generic;
using ParticlePhysics.Scenes.Kinds;

namespace ParticlePhysics.Scenes.Objects;

/// <summary>
/// <c>rods</c> and <c>cables</c>: <c>pairs</c> of global particle indices, <c>length</c> (one for all) or
/// <c>lengths</c> (one per pair), default the distance at the start. A rod holds its two particles at exactly its
/// length, a cable at most that far apart (<see cref="Constraints.RodNetwork"/>): hard constraints, not stiff springs.
/// </summary>
internal sealed class LinksKind : ISceneObjectKind
{
    private readonly bool _cables;

    private LinksKind(bool cables)
    {
        _cables = cables;
    }

    /// <summary>The <c>rods</c> kind.</summary>
    public static LinksKind Rods { get; } = new(cables: false);

    /// <summary>The <c>cables</c> kind.</summary>
    public static LinksKind Cables { get; } = new(cables: true);

    public string Name => _cables ? "cables" : "rods";

    public SceneObject Read(ObjectReader reader, SceneReadContext context)
    {
        var pairs = reader.Pairs("pairs") ?? throw reader.ObjectError($"a {Name} object needs \"pairs\": [[i, j], ...] of particle indices");
        var lengths = SpringsKind.RestLengths(reader, "length", "lengths", pairs.Count, ValueRule.Positive);
        return new LinksObject(pairs, lengths, _cables, reader.Document.File);
    }

    private sealed class LinksObject : SceneObject
    {
        private readonly List<(IndexRef First, IndexRef Second)> _pairs;
        private readonly double[]? _lengths;
        private readonly bool _cables;
        private readonly string _file;

        public LinksObject(List<(IndexRef, IndexRef)> pairs, double[]? lengths, bool cables, string file)
        {
            _pairs = pairs;
            _lengths = lengths;
            _cables = cables;
            _file = file;
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
            builder.Count(_cables ? "cables" : "rods", _pairs.Count);
            for (var r = 0; r < _pairs.Count; r++)
            {
                var (first, second) = _pairs[r];
                var length = _lengths?[r] ?? SpringsKind.StartDistance(builder, _pairs[r], _file);
                if (!(length > 0) || double.IsInfinity(1.0 / length))
                {
                    var path = first.Path.Substring(0, first.Path.Length - 3);
                    throw new SceneException(_file, path, first.Where.Line, first.Where.Column, string.Empty,
                        $"the particles start {length.ToString("R", System.Globalization.CultureInfo.InvariantCulture)} m apart, and a {(_cables ? "cable" : "rod")} needs a positive length; give \"length\"");
                }

                if (_cables)
                {
                    builder.Rods.AddCable(first.Value, second.Value, length);
                }
                else
                {
                    builder.Rods.AddRod(first.Value, second.Value, length);
                }
            }
        }
    }
}
