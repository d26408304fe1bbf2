namespace ParticlePhysics.Contacts;

/// <summary>
/// Which pairs of particles may collide (<see cref="ContactSet.PairFilter"/>): for instance not two particles of a
/// cloth that a spring already joins (<see cref="ExcludedPairs"/>). Called from within a step for each candidate pair
/// the broad phase finds, so it must be fast, deterministic and allocation-free.
/// </summary>
public interface IContactPairFilter
{
    /// <summary>True when particles <paramref name="first"/> &lt; <paramref name="second"/> may collide.</summary>
    bool MayCollide(int first, int second);
}
