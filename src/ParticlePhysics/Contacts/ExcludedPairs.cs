using System;
using System.Collections.Generic;
using ParticlePhysics.Forces;

namespace ParticlePhysics.Contacts;

/// <summary>
/// A pair filter that lets every pair collide except those it lists: typically the particles a spring joins, so that a
/// cloth collides with itself (self-collision by particle spheres) without its neighbours pushing each other apart.
/// </summary>
/// <remarks>Pairs are kept as sorted 64-bit keys (smaller index high); a query is a binary search.</remarks>
public sealed class ExcludedPairs : IContactPairFilter
{
    private readonly List<long> _pending = new();
    private long[] _keys = Array.Empty<long>();

    /// <summary>The number of distinct excluded pairs.</summary>
    public int Count
    {
        get
        {
            Seal();
            return _keys.Length;
        }
    }

    /// <summary>Excludes every pair of particles joined by a spring of <paramref name="springs"/> (a cloth's structural, shear and bend springs).</summary>
    public static ExcludedPairs FromSprings(SpringNetwork springs)
    {
        Guard.NotNull(springs, nameof(springs));
        var pairs = new ExcludedPairs();
        for (var s = 0; s < springs.Count; s++)
        {
            var (first, second) = springs.GetEnds(s);
            pairs.Add(first, second);
        }

        return pairs;
    }

    /// <summary>Excludes the pair (<paramref name="first"/>, <paramref name="second"/>), in either order.</summary>
    public void Add(int first, int second)
    {
        if (first < 0 || second < 0 || first == second)
        {
            throw new ArgumentException(
                $"A pair needs two different particle indices >= 0; got {first} and {second}.", nameof(second));
        }

        _pending.Add(Key(first, second));
    }

    /// <inheritdoc />
    public bool MayCollide(int first, int second)
    {
        Seal();
        return Array.BinarySearch(_keys, Key(first, second)) < 0;
    }

    private static long Key(int first, int second) =>
        first < second ? ((long)first << 32) | (uint)second : ((long)second << 32) | (uint)first;

    // Folds pairs added since the last query into the sorted keys (between steps, where additions happen).
    private void Seal()
    {
        if (_pending.Count == 0)
        {
            return;
        }

        var merged = new long[_keys.Length + _pending.Count];
        _keys.CopyTo(merged, 0);
        _pending.CopyTo(merged, _keys.Length);
        _pending.Clear();
        Array.Sort(merged);
        var distinct = 0;
        for (var k = 0; k < merged.Length; k++)
        {
            if (distinct == 0 || merged[k] != merged[distinct - 1])
            {
                merged[distinct++] = merged[k];
            }
        }

        Array.Resize(ref merged, distinct);
        _keys = merged;
    }
}
