using System;

namespace ParticlePhysics.Contacts;

/// <summary>
/// Which obstacles each particle came to rest on within the step, and, for the first of them, what the resting stage
/// needs: the time it came to rest, its tangential velocity relative to the obstacle then, and its place relative to
/// the obstacle then (<see cref="ContactSet"/>'s stage 4, <see cref="CoulombSlide"/>).
/// </summary>
/// <remarks>
/// A particle resting on an obstacle is held there by the resting stage, so the impact search leaves that obstacle out
/// for it (<see cref="IsRestingOn"/>). Any number of obstacles: each particle's are a short list in a shared pool of
/// entries, emptied each step and grown by doubling to the most a step has needed (it was a 64-bit mask per particle,
/// which limited a set to 64 obstacles).
/// </remarks>
internal sealed class RestingContacts
{
    private int[] _first = Array.Empty<int>();
    private double[] _time = Array.Empty<double>();
    private Vector3d[] _tangent = Array.Empty<Vector3d>();
    private Vector3d[] _point = Array.Empty<Vector3d>();
    private int[] _head = Array.Empty<int>();
    private int[] _entryObstacle = Array.Empty<int>();
    private int[] _entryNext = Array.Empty<int>();
    private int _entries;

    /// <summary>Makes room for <paramref name="count"/> particles.</summary>
    public void EnsureCapacity(int count)
    {
        if (_first.Length < count)
        {
            _first = new int[count];
            _time = new double[count];
            _tangent = new Vector3d[count];
            _point = new Vector3d[count];
            _head = new int[count];
        }
    }

    /// <summary>No particle of the first <paramref name="count"/> rests on anything.</summary>
    public void Clear(int count)
    {
        for (var i = 0; i < count; i++)
        {
            _first[i] = -1;
            _head[i] = -1;
        }

        _entries = 0;
    }

    /// <summary>The first obstacle particle <paramref name="particle"/> came to rest on in this step, or -1.</summary>
    public int FirstObstacle(int particle) => _first[particle];

    /// <summary>When, within the step, it came to rest on <see cref="FirstObstacle"/>.</summary>
    public double Time(int particle) => _time[particle];

    /// <summary>Its tangential velocity relative to that obstacle then.</summary>
    public Vector3d Tangent(int particle) => _tangent[particle];

    /// <summary>Its centre relative to that obstacle's parameters' position then.</summary>
    public Vector3d Point(int particle) => _point[particle];

    /// <summary>Whether particle <paramref name="particle"/> rests on obstacle <paramref name="obstacle"/>.</summary>
    public bool IsRestingOn(int particle, int obstacle)
    {
        for (var e = _head[particle]; e >= 0; e = _entryNext[e])
        {
            if (_entryObstacle[e] == obstacle)
            {
                return true;
            }
        }

        return false;
    }

    /// <summary>
    /// Particle <paramref name="particle"/> came to rest on <paramref name="obstacle"/> at <paramref name="time"/>; the
    /// first such obstacle of the step keeps the tangential velocity and the relative place.
    /// </summary>
    public void Rest(int particle, int obstacle, double time, Vector3d tangent, Vector3d point)
    {
        if (_first[particle] < 0)
        {
            _first[particle] = obstacle;
            _time[particle] = time;
            _tangent[particle] = tangent;
            _point[particle] = point;
        }

        if (IsRestingOn(particle, obstacle))
        {
            return;
        }

        if (_entries == _entryObstacle.Length)
        {
            var capacity = Math.Max(64, 2 * _entries);
            Array.Resize(ref _entryObstacle, capacity);
            Array.Resize(ref _entryNext, capacity);
        }

        _entryObstacle[_entries] = obstacle;
        _entryNext[_entries] = _head[particle];
        _head[particle] = _entries++;
    }
}
