using System;

namespace ParticlePhysics.Contacts;

/// <summary>
/// The impacts still to come within a step, earliest first: a binary min-heap over flat arrays that grow by doubling as
/// entries arrive, up to a limit set per step. An entry carries the epochs of its particles' paths when it was
/// computed; an entry whose particle has since changed course is stale and skipped.
/// </summary>
/// <remarks>
/// The limit bounds the work of a step (the contact set's budget of impacts), not the memory: the arrays hold what was
/// queued at once, which in a pile at rest is next to nothing, however many pairs the limit allows. (They were sized to
/// the limit up front: 16 entries of 24 bytes per candidate pair, 19 GB for 10,000 particles at one point.) Once grown
/// they stay, so a step allocates nothing after the steps before it have queued as much.
/// </remarks>
internal sealed class ImpactQueue
{
    private double[] _time = Array.Empty<double>();
    private int[] _first = Array.Empty<int>();
    private int[] _second = Array.Empty<int>();
    private int[] _firstEpoch = Array.Empty<int>();
    private int[] _secondEpoch = Array.Empty<int>();
    private int _limit;

    /// <summary>The number of queued impacts.</summary>
    public int Count { get; private set; }

    /// <summary>True once a push found the queue at its limit (the impact is then left to the end-of-step projection).</summary>
    public bool Overflowed { get; private set; }

    /// <summary>Empties the queue; it then takes up to <paramref name="limit"/> entries at once (grown as they come).</summary>
    public void Reset(int limit)
    {
        _limit = limit;
        Count = 0;
        Overflowed = false;
    }

    /// <summary>
    /// Queues an impact at <paramref name="time"/>: an obstacle impact has <paramref name="first"/> = the particle and
    /// <paramref name="second"/> = -1 - the obstacle's index; a pair impact has the pair's index in <paramref name="first"/>
    /// and <paramref name="second"/> &gt;= 0 unused (0).
    /// </summary>
    public void Push(double time, int first, int second, int firstEpoch, int secondEpoch)
    {
        if (Count == _time.Length)
        {
            if (Count >= _limit)
            {
                Overflowed = true;
                return;
            }

            Grow();
        }

        var k = Count++;
        while (k > 0)
        {
            var parent = (k - 1) / 2;
            if (!Earlier(time, first, second, parent))
            {
                break;
            }

            Move(parent, k);
            k = parent;
        }

        _time[k] = time;
        _first[k] = first;
        _second[k] = second;
        _firstEpoch[k] = firstEpoch;
        _secondEpoch[k] = secondEpoch;
    }

    /// <summary>Removes and returns the earliest impact.</summary>
    public double Pop(out int first, out int second, out int firstEpoch, out int secondEpoch)
    {
        var time = _time[0];
        first = _first[0];
        second = _second[0];
        firstEpoch = _firstEpoch[0];
        secondEpoch = _secondEpoch[0];
        var last = --Count;
        if (last > 0)
        {
            // Sift the last entry down from the root.
            double t = _time[last];
            int a = _first[last], b = _second[last], ea = _firstEpoch[last], eb = _secondEpoch[last];
            var k = 0;
            while (true)
            {
                var child = (2 * k) + 1;
                if (child >= last)
                {
                    break;
                }

                if (child + 1 < last && Earlier(_time[child + 1], _first[child + 1], _second[child + 1], child))
                {
                    child++;
                }

                if (!Earlier(_time[child], _first[child], _second[child], t, a, b))
                {
                    break;
                }

                Move(child, k);
                k = child;
            }

            _time[k] = t;
            _first[k] = a;
            _second[k] = b;
            _firstEpoch[k] = ea;
            _secondEpoch[k] = eb;
        }

        return time;
    }

    /// <summary>Doubles the arrays (at least 64 entries, at most the limit), keeping the heap.</summary>
    private void Grow()
    {
        var capacity = (int)Math.Min(_limit, Math.Max(64L, 2L * _time.Length));
        Array.Resize(ref _time, capacity);
        Array.Resize(ref _first, capacity);
        Array.Resize(ref _second, capacity);
        Array.Resize(ref _firstEpoch, capacity);
        Array.Resize(ref _secondEpoch, capacity);
    }

    // Ties are broken by the indices, so that the order, and with it the result, is the same on every run.
    private bool Earlier(double time, int first, int second, int slot) =>
        Earlier(time, first, second, _time[slot], _first[slot], _second[slot]);

    private static bool Earlier(double time, int first, int second, double otherTime, int otherFirst, int otherSecond) =>
        time < otherTime || (time == otherTime && (first < otherFirst || (first == otherFirst && second < otherSecond)));

    private void Move(int from, int to)
    {
        _time[to] = _time[from];
        _first[to] = _first[from];
        _second[to] = _second[from];
        _firstEpoch[to] = _firstEpoch[from];
        _secondEpoch[to] = _secondEpoch[from];
    }
}
