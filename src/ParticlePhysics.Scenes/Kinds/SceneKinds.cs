using System;
using System.Collections.Generic;
using System.Linq;
using ParticlePhysics.Scenes.Colliders;
using ParticlePhysics.Scenes.Objects;

namespace ParticlePhysics.Scenes.Kinds;

/// <summary>
/// The registry of the kinds a scene may name in <c>"type"</c>: objects and colliders by name. Adding a kind is a
/// class of its own (an <see cref="ISceneObjectKind"/> or <see cref="IColliderKind"/>) and one line in
/// <see cref="CreateDefault"/>; the contract's kinds whose issue has not landed are registered as
/// <see cref="NotBuiltYet"/>, refused with the issue that brings them.
/// </summary>
internal sealed class SceneKinds
{
    private readonly Dictionary<string, ISceneObjectKind> _objects = new(StringComparer.Ordinal);
    private readonly Dictionary<string, IColliderKind> _colliders = new(StringComparer.Ordinal);

    /// <summary>Every kind of this version.</summary>
    public static SceneKinds Default { get; } = CreateDefault();

    public IReadOnlyDictionary<string, ISceneObjectKind> Objects => _objects;

    public IReadOnlyDictionary<string, IColliderKind> Colliders => _colliders;

    public static SceneKinds CreateDefault()
    {
        var kinds = new SceneKinds();
        kinds.Add(new ParticlesKind());
        kinds.Add(new SpringsKind());
        kinds.Add(LinksKind.Rods);
        kinds.Add(LinksKind.Cables);
        kinds.Add(new LoadKind());
        kinds.Add(new ClothKind());
        kinds.Add(new RopeKind());
        kinds.Add(SolidKind.Rigid);
        kinds.Add(SolidKind.Soft);
        kinds.Add(new GranularKind());
        kinds.Add(new FluidKind());

        kinds.Add(new PlaneKind());
        kinds.Add(new SphereKind());
        kinds.Add(new CapsuleKind());
        kinds.Add(new BoxKind());
        kinds.Add(new MeshKind());
        kinds.Add(new HeightFieldKind());
        return kinds;
    }

    public void Add(ISceneObjectKind kind) => _objects.Add(kind.Name, kind);

    public void Add(IColliderKind kind) => _colliders.Add(kind.Name, kind);

    /// <summary>The names of the kinds built in this version ("particles, springs, ...").</summary>
    public string BuiltList(bool colliders) => string.Join(", ", colliders
        ? _colliders.Values.Where(k => k is not NotBuiltYet).Select(k => k.Name)
        : _objects.Values.Where(k => k is not NotBuiltYet).Select(k => k.Name));

    /// <summary>Every name, built or not.</summary>
    public IEnumerable<string> Names(bool colliders) => colliders ? _colliders.Keys : _objects.Keys;
}
