using System;

namespace ParticlePhysics;

/// <summary>
/// The islands of the world's sleeping: the sets of particles that are tied together (a body), found by union-find
/// (union by size, path halving) over the links the generators and constraint sets add. Links to a pinned particle
/// are ignored: a pinned particle is ground, and two piles resting on the same pinned particle are two islands.
/// </summary>
public sealed class ParticleIslands
{
    private int[] _parent = Array.Empty<int>();
    private int[] _size = Array.Empty<int>();
    private bool[] _ground = Array.Empty<bool>();
    private int _count;

    /// <summary>How many particles the islands cover (the world's count).</summary>
    public int Count => _count;

    /// <summary>Puts every particle in an island of its own; <paramref name="ground"/> marks those no link may pass through.</summary>
    internal void Reset(int count, bool[] ground)
    {
        if (_parent.Length < count)
        {
            _parent = new int[count];
            _size = new int[count];
            _ground = new bool[count];
        }

        _count = count;
        for (var i = 0; i < count; i++)
        {
            _parent[i] = i;
            _size[i] = 1;
            _ground[i] = ground[i];
        }
    }

    /// <summary>Puts particles a and b in one island (nothing if either is pinned, or out of range).</summary>
    public void Link(int a, int b)
    {
        if ((uint)a >= (uint)_count || (uint)b >= (uint)_count || _ground[a] || _ground[b])
        {
            return;
        }

        var ra = Find(a);
        var rb = Find(b);
        if (ra == rb)
        {
            return;
        }

        // The smaller under the larger, ties by index, so that the roots do not depend on anything but the links' order.
        if (_size[ra] < _size[rb] || (_size[ra] == _size[rb] && rb < ra))
        {
            (ra, rb) = (rb, ra);
        }

        _parent[rb] = ra;
        _size[ra] += _size[rb];
    }

    /// <summary>The island of particle i, named by one of its particles.</summary>
    public int Find(int i)
    {
        while (_parent[i] != i)
        {
            _parent[i] = _parent[_parent[i]];
            i = _parent[i];
        }

        return i;
    }
}
