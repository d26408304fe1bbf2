using System;
using System.Globalization;

namespace ParticlePhysics.Contacts;

/// <summary>
/// Which contacts happen, by layers and masks (as Box2D's category and mask bits): a group of particles (a cloth, a
/// rope, a body: <see cref="ContactSet.SetParticleFilter"/>) and an obstacle (<see cref="Obstacle.Filter"/>) each
/// belong to some of 32 layers and collide with the layers of their mask; two of them meet only when each is in a
/// layer of the other's mask. The default is layer 1 (bit 0) and a mask of every layer, so that everything collides
/// until told otherwise.
/// </summary>
/// <example>
/// A cloth that ignores a hand's colliders but lies on the floor: the cloth in layer 2 with a mask without layer 3,
/// the hand's obstacles in layer 3; the floor keeps the default.
/// <code>
/// contacts.SetParticleFilter(firstClothParticle, clothParticles, new CollisionFilter(layers: 2, mask: ~4u));
/// hand.Filter = new CollisionFilter(layers: 4, mask: uint.MaxValue);
/// </code>
/// </example>
public readonly struct CollisionFilter : IEquatable<CollisionFilter>
{
    // Stored so that default(CollisionFilter) is Default: layer 1 and every layer in the mask.
    private readonly uint _layersFromDefault;
    private readonly uint _maskFromDefault;

    /// <summary>Creates a filter.</summary>
    /// <param name="layers">The layers it belongs to, one bit each (any value; 0 collides with nothing).</param>
    /// <param name="mask">The layers it collides with.</param>
    public CollisionFilter(uint layers, uint mask)
    {
        _layersFromDefault = layers ^ 1u;
        _maskFromDefault = ~mask;
    }

    /// <summary>Layer 1, colliding with every layer: what particles and obstacles have until set otherwise.</summary>
    public static CollisionFilter Default => default;

    /// <summary>The layers it belongs to, one bit each.</summary>
    public uint Layers => _layersFromDefault ^ 1u;

    /// <summary>The layers it collides with.</summary>
    public uint Mask => ~_maskFromDefault;

    /// <summary>Two filters are equal when their layers and masks are.</summary>
    public static bool operator ==(CollisionFilter left, CollisionFilter right) => left.Equals(right);

    /// <summary>Two filters differ when their layers or masks do.</summary>
    public static bool operator !=(CollisionFilter left, CollisionFilter right) => !left.Equals(right);

    /// <summary>Whether this and <paramref name="other"/> collide: each is in a layer of the other's mask.</summary>
    public bool Accepts(CollisionFilter other) => (Layers & other.Mask) != 0 && (other.Layers & Mask) != 0;

    /// <inheritdoc />
    public bool Equals(CollisionFilter other) =>
        _layersFromDefault == other._layersFromDefault && _maskFromDefault == other._maskFromDefault;

    /// <inheritdoc />
    public override bool Equals(object? obj) => obj is CollisionFilter other && Equals(other);

    /// <inheritdoc />
    public override int GetHashCode() => unchecked((int)(_layersFromDefault * 2654435761u) ^ (int)_maskFromDefault);

    /// <inheritdoc />
    public override string ToString() =>
        string.Format(CultureInfo.InvariantCulture, "layers 0x{0:X8}, mask 0x{1:X8}", Layers, Mask);
}
