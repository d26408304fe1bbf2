using System;
using System.Collections.Generic;
using ParticlePhysics.Contacts;

namespace ParticlePhysics.Demo.Animation;

/// <summary>What a link between two points is, which sets how the replay draws it.</summary>
internal enum LinkKind
{
    /// <summary>A spring (any stiffness, rest length or damping): a thin line.</summary>
    Spring,

    /// <summary>A rod, held at a fixed length: a thick dark line.</summary>
    Rod,

    /// <summary>A cable, at most its length apart: a line, dashed while slack.</summary>
    Cable,
}

/// <summary>
/// A link between two ends. An end is a particle index (0 to <see cref="ReplayScene.ParticleCount"/> - 1) or, for
/// a fixed anchor, <see cref="ReplayScene.ParticleCount"/> + the anchor's index in <see cref="ReplayScene.Anchors"/>.
/// <see cref="Length"/> is a cable's length (drawn dashed while shorter, slack), 0 for the other kinds.
/// </summary>
internal readonly record struct ReplayLink(int First, int Second, LinkKind Kind, double Length = 0);

/// <summary>
/// A collider as the replay draws it: the core's description of the obstacle at t = 0 (<see cref="ObstacleShape"/>)
/// and its velocity. The core moves an obstacle by translation at its velocity, so the page draws it at
/// <c>Shape.Center + t Velocity</c> at every time t of the run (still when the velocity is zero).
/// </summary>
internal readonly record struct ReplayCollider(ObstacleShape Shape, Vector3d Velocity);

/// <summary>
/// The parts of a replay that do not move with the frames: each particle's radius (0: a point) and whether it is
/// pinned, the links (springs, rods, cables) by their ends, fixed anchors, a surface to shade (the cloth's
/// triangles) and the colliders (the core's obstacle descriptions). <see cref="SceneReader"/> fills it from a world.
/// </summary>
internal sealed class ReplayScene
{
    private readonly List<ReplayLink> _links = new();
    private readonly List<Vector3d> _anchors = new();
    private readonly List<int> _triangles = new();
    private readonly List<ReplayCollider> _colliders = new();
    private readonly List<int> _pinned = new();
    private readonly List<(int Particle, Vector3d Force)> _loads = new();

    public ReplayScene(int particleCount)
    {
        ParticleCount = particleCount;
        Radii = new double[particleCount];
    }

    /// <summary>The number of particles (each frame holds 3 coordinates per particle).</summary>
    public int ParticleCount { get; }

    /// <summary>Each particle's radius in m; 0 draws it as a dot of a fixed size on screen.</summary>
    public double[] Radii { get; }

    /// <summary>The pinned particles, in increasing order.</summary>
    public IReadOnlyList<int> Pinned => _pinned;

    /// <summary>The fixed anchor points that links end at.</summary>
    public IReadOnlyList<Vector3d> Anchors => _anchors;

    /// <summary>The links, in the order they were added.</summary>
    public IReadOnlyList<ReplayLink> Links => _links;

    /// <summary>A surface to shade: three particle indices per triangle (empty when there is none).</summary>
    public IReadOnlyList<int> Triangles => _triangles;

    /// <summary>Constant forces on particles (a scene's loads), drawn as arrows.</summary>
    public IReadOnlyList<(int Particle, Vector3d Force)> Loads => _loads;

    /// <summary>The colliders.</summary>
    public IReadOnlyList<ReplayCollider> Colliders => _colliders;

    /// <summary>Marks <paramref name="particle"/> as pinned.</summary>
    public void Pin(int particle)
    {
        CheckParticle(particle, nameof(particle));
        var at = _pinned.BinarySearch(particle);
        if (at < 0)
        {
            _pinned.Insert(~at, particle);
        }
    }

    /// <summary>Sets the radius of <paramref name="particle"/> (a finite number &gt;= 0, in m).</summary>
    public void SetRadius(int particle, double radius)
    {
        CheckParticle(particle, nameof(particle));
        if (!(radius >= 0) || !double.IsFinite(radius))
        {
            throw new ArgumentOutOfRangeException(nameof(radius), radius, "a radius must be a finite number >= 0.");
        }

        Radii[particle] = radius;
    }

    /// <summary>A link between two particles; <paramref name="length"/> is a cable's length (0 otherwise).</summary>
    public void AddLink(int first, int second, LinkKind kind, double length = 0)
    {
        CheckParticle(first, nameof(first));
        CheckParticle(second, nameof(second));
        _links.Add(new ReplayLink(first, second, kind, length));
    }

    /// <summary>A link between a particle and a fixed point (anchors at the same point are shared).</summary>
    public void AddAnchoredLink(int particle, Vector3d anchor, LinkKind kind, double length = 0)
    {
        CheckParticle(particle, nameof(particle));
        var index = _anchors.IndexOf(anchor);
        if (index < 0)
        {
            index = _anchors.Count;
            _anchors.Add(anchor);
        }

        _links.Add(new ReplayLink(particle, ParticleCount + index, kind, length));
    }

    /// <summary>A triangle of the surface, by its three particles.</summary>
    public void AddTriangle(int a, int b, int c)
    {
        CheckParticle(a, nameof(a));
        CheckParticle(b, nameof(b));
        CheckParticle(c, nameof(c));
        _triangles.Add(a);
        _triangles.Add(b);
        _triangles.Add(c);
    }

    /// <summary>A constant force <paramref name="force"/> (N) on <paramref name="particle"/>, drawn as an arrow.</summary>
    public void AddLoad(int particle, Vector3d force)
    {
        CheckParticle(particle, nameof(particle));
        _loads.Add((particle, force));
    }

    /// <summary>A collider to draw: its shape at t = 0 and its velocity (zero for a still one).</summary>
    public void AddCollider(ObstacleShape shape, Vector3d velocity = default) => _colliders.Add(new ReplayCollider(shape, velocity));

    private void CheckParticle(int particle, string name)
    {
        if ((uint)particle >= (uint)ParticleCount)
        {
            throw new ArgumentOutOfRangeException(name, particle, $"{name} must be a particle index from 0 to {ParticleCount - 1}.");
        }
    }
}
