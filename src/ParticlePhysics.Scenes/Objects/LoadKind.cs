using System.Collections.Generic;
using ParticlePhysics.Scenes.Kinds;

namespace ParticlePhysics.Scenes.Objects;

/// <summary><c>load</c>: <c>particles</c> (global indices) and <c>force</c> [fx, fy, fz] in N, a constant force on each of them.</summary>
internal sealed class LoadKind : ISceneObjectKind
{
    public string Name => "load";

    public SceneObject Read(ObjectReader reader, SceneReadContext context)
    {
        var particles = reader.Indices("particles") ?? throw reader.ObjectError("a load object needs \"particles\": [i, ...], the particles it pushes");
        var force = reader.Vector("force", null, "N");
        return new LoadObject(particles, force);
    }

    private sealed class LoadObject : SceneObject
    {
        private readonly List<IndexRef> _particles;
        private readonly Vector3d _force;

        public LoadObject(List<IndexRef> particles, Vector3d force)
        {
            _particles = particles;
            _force = force;
        }

        public override void CheckIndices(SceneIndexCheck check)
        {
            foreach (var p in _particles)
            {
                check.Particle(p);
            }
        }

        public override void AddElements(SceneBuilder builder)
        {
            builder.Count("loads", _particles.Count);
            foreach (var p in _particles)
            {
                builder.Loads.Add(p.Value, _force);
            }
        }
    }
}
