using ParticlePhysics.Cloth;
using ParticlePhysics.Contacts;

namespace ParticlePhysics.Scenarios;

/// <summary>
/// The contract's drape: the <see cref="ClothScenario"/> cloth (here pinned nowhere by default), every particle of
/// radius r, falling from y = 0 onto a sphere of radius R centred at (S/2, y_s, S/2), with friction mu and restitution
/// 0. The cloth also collides with itself (particle spheres; pairs joined by a spring excluded). No exact solution: no
/// particle enters the sphere, the middle comes to rest on its top, the rest hangs around it.
/// </summary>
public sealed class DrapeScenario
{
    /// <summary>The contract's default time step, in seconds.</summary>
    public const double DefaultTimeStep = 0.001;

    /// <summary>The contract's default duration, in seconds.</summary>
    public const double DefaultDuration = 3;

    private double _radius = 0.01, _sphereRadius = 0.3, _sphereY = -0.5, _friction = 0.5;

    /// <summary>The cloth: size, resolution, mass, springs, drag, gravity, pins (default: none).</summary>
    public ClothScenario Cloth { get; } = new() { Pinning = ClothPinning.None };

    /// <summary>The radius r of every particle, in m (default 0.01).</summary>
    public double Radius { get => _radius; set { Guard.NonNegativeFinite(value, nameof(Radius)); _radius = value; } }

    /// <summary>The sphere's radius R, in m (default 0.3).</summary>
    public double SphereRadius { get => _sphereRadius; set { Guard.PositiveFinite(value, nameof(SphereRadius)); _sphereRadius = value; } }

    /// <summary>The height y_s of the sphere's centre, in m (default -0.5).</summary>
    public double SphereY { get => _sphereY; set { Guard.Finite(value, nameof(SphereY)); _sphereY = value; } }

    /// <summary>The sphere's friction mu (default 0.5).</summary>
    public double Friction { get => _friction; set { Guard.NonNegativeFinite(value, nameof(Friction)); _friction = value; } }

    /// <summary>The sphere's centre: (S/2, y_s, S/2).</summary>
    public Vector3d SphereCenter => new(0.5 * Cloth.Size, _sphereY, 0.5 * Cloth.Size);

    /// <summary>Builds the world: the cloth, the radii, and a contact set with the sphere and self-collision.</summary>
    public ParticleWorld Build() => BuildCloth().System;

    /// <summary>Builds the cloth (with its mesh and springs) in its world, with the radii and the contact set.</summary>
    public ParticleCloth BuildCloth()
    {
        var cloth = Cloth.CreateBuilder().Build();
        var world = cloth.System;
        for (var i = 0; i < world.Count; i++)
        {
            world.SetRadius(i, _radius);
        }

        var contacts = new ContactSet
        {
            ParticleCollisions = _radius > 0.0,
            PairFilter = ExcludedPairs.FromSprings(cloth.Springs),
        };
        contacts.Add(new SphereObstacle(SphereCenter, _sphereRadius, restitution: 0.0, friction: _friction));
        world.AddConstraints(contacts);
        return cloth;
    }
}
