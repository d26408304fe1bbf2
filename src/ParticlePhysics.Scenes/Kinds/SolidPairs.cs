using ParticlePhysics.Contacts;

namespace ParticlePhysics.Scenes.Kinds;

/// <summary>
/// A scene without <c>particleCollisions</c> that holds solids (bodies, granular matter): a pair collides only when
/// one of its particles is a solid's, so that solids meet everything while cloth and loose particles keep the
/// contract's default of passing through each other. The rest is left to <see cref="IContactPairFilter"/> next.
/// </summary>
internal sealed class SolidPairs : IContactPairFilter
{
    private readonly bool[] _solid;
    private readonly IContactPairFilter? _next;

    public SolidPairs(bool[] solid, IContactPairFilter? next)
    {
        _solid = solid;
        _next = next;
    }

    public bool MayCollide(int first, int second) =>
        (_solid[first] || _solid[second]) && (_next is null || _next.MayCollide(first, second));
}
