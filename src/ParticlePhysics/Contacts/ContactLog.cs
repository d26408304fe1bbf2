using System;

namespace ParticlePhysics.Contacts;

/// <summary>
/// What the last step shows a caller (<see cref="ContactSet.Impacts"/>, <see cref="ContactSet.ImpactCount"/>,
/// <see cref="ContactSet.CandidatePairCount"/>), and the copy kept aside at the start of a step so that a failed step
/// shows the last committed one again (<see cref="IStatefulConstraintSet"/>).
/// </summary>
internal sealed class ContactLog
{
    private readonly ContactImpact[] _impacts;
    private ContactImpact[] _saved = Array.Empty<ContactImpact>();
    private int _savedCount;
    private int _savedPairs;

    /// <summary>A log that keeps the first <paramref name="capacity"/> impacts of a step.</summary>
    public ContactLog(int capacity) => _impacts = new ContactImpact[capacity];

    /// <summary>The impacts counted since <see cref="Clear"/> (only the first <c>capacity</c> are kept).</summary>
    public int Count { get; private set; }

    /// <summary>The candidate pairs of the last step or substep.</summary>
    public int CandidatePairs { get; set; }

    /// <summary>The impacts kept, in the order they were recorded.</summary>
    public ReadOnlySpan<ContactImpact> Impacts => _impacts.AsSpan(0, Math.Min(Count, _impacts.Length));

    /// <summary>A new step or substep: no impacts, no pairs.</summary>
    public void Clear()
    {
        Count = 0;
        CandidatePairs = 0;
    }

    /// <summary>Counts an impact, and keeps it while there is room.</summary>
    public void Record(double time, int particle, int other, bool withObstacle, double speed, bool resting)
    {
        if (Count < _impacts.Length)
        {
            _impacts[Count] = new ContactImpact(time, particle, other, withObstacle, speed, resting);
        }

        Count++;
    }

    /// <summary>Keeps the log aside (a copy allocated once).</summary>
    public void Save()
    {
        if (_saved.Length == 0)
        {
            _saved = new ContactImpact[_impacts.Length];
        }

        _savedCount = Count;
        _savedPairs = CandidatePairs;
        Impacts.CopyTo(_saved);
    }

    /// <summary>Shows the log kept aside by <see cref="Save"/> again.</summary>
    public void Restore()
    {
        Count = _savedCount;
        CandidatePairs = _savedPairs;
        _saved.AsSpan(0, Math.Min(Count, _impacts.Length)).CopyTo(_impacts);
    }
}
