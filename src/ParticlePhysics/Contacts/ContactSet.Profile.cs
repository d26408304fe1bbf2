using System.Diagnostics;
using ParticlePhysics.Internal;

namespace ParticlePhysics.Contacts;

// The contact stage's part of the world's step profile (StepProfile): the time of its broad phase, the candidate pairs
// it listed and the contacts it resolved, added up while the world profiles a step. Off, it reads no clock.
public sealed partial class ContactSet : IContactStage
{
    private bool _profiling;
    private long _broadPhaseTicks;
    private int _profiledPairs;
    private int _profiledContacts;

    void IContactStage.BeginProfile()
    {
        _profiling = true;
        _broadPhaseTicks = 0;
        _profiledPairs = 0;
        _profiledContacts = 0;
    }

    void IContactStage.EndProfile(out long broadPhaseTicks, out int pairs, out int contacts)
    {
        _profiling = false;
        broadPhaseTicks = _broadPhaseTicks;
        pairs = _profiledPairs;
        contacts = _profiledContacts;
    }

    /// <summary>The clock now when the world profiles the step, else 0 (and no clock read).</summary>
    private long BroadPhaseStart() => _profiling ? Stopwatch.GetTimestamp() : 0;

    /// <summary>A broad phase that began at <paramref name="started"/> ends, having listed <paramref name="pairs"/> pairs.</summary>
    private void BroadPhaseEnd(long started, int pairs)
    {
        if (_profiling)
        {
            _broadPhaseTicks += Stopwatch.GetTimestamp() - started;
            _profiledPairs += pairs;
        }
    }

    /// <summary>A call resolved <paramref name="contacts"/> contacts (impacts, and particles touching an obstacle at its end).</summary>
    private void CountContacts(int contacts)
    {
        if (_profiling)
        {
            _profiledContacts += contacts;
        }
    }
}
