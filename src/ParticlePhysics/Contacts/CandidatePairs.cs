using System;

namespace ParticlePhysics.Contacts;

/// <summary>
/// The particle pairs of one step that may meet (the broad phase's pairs that survive the narrow test), whether each has
/// come to rest, and each particle's pairs (an index by particle, CSR: the pairs of particle i are
/// <c>PairAt(k)</c> for k from <see cref="StartOf"/>(i) to <see cref="StartOf"/>(i + 1)).
/// </summary>
/// <remarks>
/// The order of the pairs is the broad phase's (the order of its cells), which is the order every later stage walks
/// them in: the Gauss-Seidel order of the separation. The lists grow by doubling to the most pairs a step has found
/// (about 40 bytes a pair) and are kept, so a step allocates nothing once the steps before it found as many.
/// </remarks>
internal sealed class CandidatePairs
{
    private int[] _first = Array.Empty<int>();
    private int[] _second = Array.Empty<int>();
    private bool[] _resting = Array.Empty<bool>();
    private int[] _startOf = Array.Empty<int>();
    private int[] _pairsOf = Array.Empty<int>();

    /// <summary>The number of pairs.</summary>
    public int Count { get; private set; }

    /// <summary>The first (smaller) particle of each pair.</summary>
    public Span<int> First => _first.AsSpan(0, Count);

    /// <summary>The second (larger) particle of each pair.</summary>
    public Span<int> Second => _second.AsSpan(0, Count);

    /// <summary>Makes room for the index of <paramref name="particles"/> particles.</summary>
    public void EnsureParticles(int particles)
    {
        if (_startOf.Length < particles + 1)
        {
            _startOf = new int[particles + 1];
        }
    }

    /// <summary>Empties the list and makes room for <paramref name="pairs"/> pairs (at most <paramref name="limit"/>).</summary>
    public void Reset(int pairs, int limit)
    {
        Count = 0;
        if (_first.Length < pairs)
        {
            var capacity = Math.Max(pairs, (int)Math.Min(2L * _first.Length, limit));
            _first = new int[capacity];
            _second = new int[capacity];
            _resting = new bool[capacity];
            _pairsOf = new int[2 * capacity];
        }
    }

    /// <summary>Empties the list.</summary>
    public void Clear() => Count = 0;

    /// <summary>Appends the pair (<paramref name="first"/>, <paramref name="second"/>), not resting; room was made by <see cref="Reset"/>.</summary>
    public void Add(int first, int second)
    {
        _first[Count] = first;
        _second[Count] = second;
        _resting[Count] = false;
        Count++;
    }

    /// <summary>Whether pair <paramref name="pair"/> came to rest in this step (its impacts are over).</summary>
    public bool IsResting(int pair) => _resting[pair];

    /// <summary>Pair <paramref name="pair"/> came to rest.</summary>
    public void MarkResting(int pair) => _resting[pair] = true;

    /// <summary>Pair <paramref name="pair"/> rests no longer (a bounce of one of its particles changed its course).</summary>
    public void ClearResting(int pair) => _resting[pair] = false;

    /// <summary>Where particle <paramref name="particle"/>'s pairs start in the index (the next particle's start ends them).</summary>
    public int StartOf(int particle) => _startOf[particle];

    /// <summary>The pair at place <paramref name="k"/> of the index.</summary>
    public int PairAt(int k) => _pairsOf[k];

    /// <summary>Each particle's pairs, in pair order (a counting sort of both ends).</summary>
    public void IndexByParticle(int particles)
    {
        var count = Count;
        Array.Clear(_startOf, 0, particles + 1);
        for (var p = 0; p < count; p++)
        {
            _startOf[_first[p] + 1]++;
            _startOf[_second[p] + 1]++;
        }

        for (var i = 0; i < particles; i++)
        {
            _startOf[i + 1] += _startOf[i];
        }

        for (var p = 0; p < count; p++)
        {
            _pairsOf[_startOf[_first[p]]++] = p;
            _pairsOf[_startOf[_second[p]]++] = p;
        }

        for (var i = particles; i > 0; i--)
        {
            _startOf[i] = _startOf[i - 1];
        }

        _startOf[0] = 0;
    }
}
