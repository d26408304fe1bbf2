using ParticlePhysics.Contacts;

namespace ParticlePhysics.Bodies;

/// <summary>
/// The contact pair filter of a <see cref="ShapeMatching"/> set: two particles of one body never collide (its shape
/// holds them apart), everything else is left to <see cref="Next"/> (every pair when it is null).
/// </summary>
public sealed class BodyPairFilter : IContactPairFilter
{
    private readonly ShapeMatching _bodies;

    internal BodyPairFilter(ShapeMatching bodies)
    {
        _bodies = bodies;
    }

    /// <summary>The filter asked about pairs from two bodies or none (a cloth's <see cref="ExcludedPairs"/>), or null.</summary>
    public IContactPairFilter? Next { get; set; }

    /// <inheritdoc />
    public bool MayCollide(int first, int second)
    {
        var body = _bodies.BodyOfParticle(first);
        if (body >= 0 && body == _bodies.BodyOfParticle(second))
        {
            return false;
        }

        return Next is null || Next.MayCollide(first, second);
    }
}
