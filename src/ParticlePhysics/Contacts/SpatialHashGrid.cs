using System;
using System.Runtime.CompilerServices;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Contacts;

/// <summary>
/// The broad phase: every pair of axis-aligned boxes that overlap, among N boxes, in O(N) time and without allocation
/// once its buffers have grown to the largest N (a sorted uniform grid, as in Teschner et al.'s spatial hashing).
/// </summary>
/// <remarks>
/// <para>
/// The cell size h is the largest extent of the "ordinary" boxes, those no larger than 4 times the mean; each ordinary
/// box goes into the cell of its centre, so two that overlap have centres at most h apart on each axis, in the same or
/// adjacent cells: each box looks at its own cell and the 13 of the 26 around it that come after it in lexicographic
/// order, so that each pair of neighbouring cells is visited once. Cells are hashed into a table of 2^k &gt;= 2 N
/// buckets, and the boxes are counting-sorted by bucket (stable, so every run visits them in the same order); a box
/// found in a bucket is a neighbour only if its own cell is the one visited, so hash collisions neither duplicate nor
/// invent pairs. The few larger boxes (a particle moving very fast) are tested against every box.
/// </para>
/// <para>Each overlapping pair is reported once, as (i, j) with i &lt; j, in a deterministic order.</para>
/// </remarks>
public sealed class SpatialHashGrid
{
    private const int LargeFactor = 4;

    // Cell coordinates are clamped to 21 bits each (+-1,048,574 cells) so that three pack into one long; clamping
    // merges far cells, which costs time, never a pair (the overlap test decides).
    private const long CoordinateLimit = (1L << 20) - 2;

    // The cell itself, then the 13 neighbours (dx, dy, dz) that come after it in lexicographic order.
    private static readonly int[] _forward =
    {
        0, 0, 0, 0, 0, 1, 0, 1, -1, 0, 1, 0, 0, 1, 1, 1, -1, -1, 1, -1, 0, 1, -1, 1, 1, 0, -1, 1, 0, 0, 1, 0, 1, 1, 1, -1,
        1, 1, 0, 1, 1, 1,
    };
    private double[] _min = Array.Empty<double>();
    private double[] _max = Array.Empty<double>();
    private long[] _cells = Array.Empty<long>();
    private int[] _bucketStart = Array.Empty<int>();
    private int[] _sorted = Array.Empty<int>();
    private int[] _bucketOf = Array.Empty<int>();
    private int[] _large = Array.Empty<int>();
    private int[] _first = Array.Empty<int>();
    private int[] _second = Array.Empty<int>();
    private int _count;
    private int _largeCount;
    private int _pairCount;
    private int _mask;
    private double _cellSize;

    /// <summary>The number of pairs the last <see cref="FindPairs"/> found.</summary>
    public int PairCount => _pairCount;

    /// <summary>The first (smaller) index of each pair the last <see cref="FindPairs"/> found.</summary>
    public ReadOnlySpan<int> First => _first.AsSpan(0, _pairCount);

    /// <summary>The second (larger) index of each pair.</summary>
    public ReadOnlySpan<int> Second => _second.AsSpan(0, _pairCount);

    /// <summary>The cell size of the last build, in metres.</summary>
    public double CellSize => _cellSize;

    /// <summary>
    /// Finds every pair of overlapping boxes (touching counts) among <paramref name="count"/> boxes, box i being
    /// [min[3i..3i+2], max[3i..3i+2]]; <paramref name="filter"/>, if not null, drops pairs it refuses.
    /// </summary>
    public void FindPairs(ReadOnlySpan<double> min, ReadOnlySpan<double> max, int count, IContactPairFilter? filter = null)
    {
        if (count < 0 || min.Length < 3 * count || max.Length < 3 * count)
        {
            throw new ArgumentException($"min and max need 3 values for each of the {count} boxes.", nameof(count));
        }

        Build(min, max, count);
        _pairCount = 0;
        for (var i = 0; i < count; i++)
        {
            if (_bucketOf[i] < 0)
            {
                continue; // a large box: paired below
            }

            UnpackCell(_cells[i], out var cx, out var cy, out var cz);
            for (var offset = 0; offset < 14; offset++)
            {
                // Its own cell (later boxes only), then the 13 neighbours of the forward half (each pair of cells once).
                var cell = PackCell(cx + _forward[3 * offset], cy + _forward[(3 * offset) + 1], cz + _forward[(3 * offset) + 2]);
                var bucket = Bucket(cell);
                for (var k = _bucketStart[bucket]; k < _bucketStart[bucket + 1]; k++)
                {
                    var j = _sorted[k];
                    if ((offset > 0 || j > i) && _cells[j] == cell && Overlap(i, j))
                    {
                        Emit(Math.Min(i, j), Math.Max(i, j), filter);
                    }
                }
            }
        }

        for (var l = 0; l < _largeCount; l++)
        {
            var i = _large[l];
            for (var j = 0; j < count; j++)
            {
                // Against every ordinary box, and against the large boxes after it (each such pair once).
                if (j != i && (_bucketOf[j] >= 0 || j > i) && Overlap(i, j))
                {
                    Emit(Math.Min(i, j), Math.Max(i, j), filter);
                }
            }
        }
    }

    private void Build(ReadOnlySpan<double> min, ReadOnlySpan<double> max, int count)
    {
        if (_bucketOf.Length < count)
        {
            _min = new double[3 * count];
            _max = new double[3 * count];
            _cells = new long[count];
            _sorted = new int[count];
            _bucketOf = new int[count];
            _large = new int[count];
        }

        var buckets = 2;
        while (buckets < 2 * count)
        {
            buckets *= 2;
        }

        if (_bucketStart.Length < buckets + 1)
        {
            _bucketStart = new int[buckets + 1];
        }

        _mask = buckets - 1;
        _count = count;
        var lo = min.ForReading();
        var hi = max.ForReading();
        var sum = 0.0;
        for (var k = 0; k < 3 * count; k++)
        {
            _min[k] = lo[k];
            _max[k] = hi[k];
        }

        for (var i = 0; i < count; i++)
        {
            sum += Extent(i);
        }

        var limit = count == 0 ? 0.0 : LargeFactor * sum / count;
        var cell = 0.0;
        for (var i = 0; i < count; i++)
        {
            var extent = Extent(i);
            if (extent <= limit)
            {
                cell = Math.Max(cell, extent);
            }
        }

        _cellSize = cell > 0.0 ? cell : 1.0;
        var inverse = 1.0 / _cellSize;
        Array.Clear(_bucketStart, 0, buckets + 1);
        _largeCount = 0;
        for (var i = 0; i < count; i++)
        {
            if (Extent(i) > limit)
            {
                _bucketOf[i] = -1;
                _large[_largeCount++] = i;
                continue;
            }

            var o = 3 * i;
            _cells[i] = PackCell(
                CellCoordinate(0.5 * (_min[o] + _max[o]) * inverse),
                CellCoordinate(0.5 * (_min[o + 1] + _max[o + 1]) * inverse),
                CellCoordinate(0.5 * (_min[o + 2] + _max[o + 2]) * inverse));
            var bucket = Bucket(_cells[i]);
            _bucketOf[i] = bucket;
            _bucketStart[bucket + 1]++;
        }

        for (var b = 0; b < buckets; b++)
        {
            _bucketStart[b + 1] += _bucketStart[b];
        }

        // Counting sort by bucket: a second pass places each box after those of lower index in its bucket.
        for (var i = 0; i < count; i++)
        {
            var bucket = _bucketOf[i];
            if (bucket >= 0)
            {
                _sorted[_bucketStart[bucket]++] = i;
            }
        }

        for (var b = buckets; b > 0; b--)
        {
            _bucketStart[b] = _bucketStart[b - 1];
        }

        _bucketStart[0] = 0;
    }

    private void Emit(int i, int j, IContactPairFilter? filter)
    {
        if (filter is not null && !filter.MayCollide(i, j))
        {
            return;
        }

        if (_pairCount == _first.Length)
        {
            var capacity = Math.Max(64, 2 * _first.Length);
            Array.Resize(ref _first, capacity);
            Array.Resize(ref _second, capacity);
        }

        _first[_pairCount] = i;
        _second[_pairCount] = j;
        _pairCount++;
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private bool Overlap(int i, int j)
    {
        var a = 3 * i;
        var b = 3 * j;
        return _min[a] <= _max[b] && _min[b] <= _max[a]
            && _min[a + 1] <= _max[b + 1] && _min[b + 1] <= _max[a + 1]
            && _min[a + 2] <= _max[b + 2] && _min[b + 2] <= _max[a + 2];
    }

    private double Extent(int i)
    {
        var o = 3 * i;
        return Math.Max(_max[o] - _min[o], Math.Max(_max[o + 1] - _min[o + 1], _max[o + 2] - _min[o + 2]));
    }

    private static long CellCoordinate(double scaled)
    {
        var floor = Math.Floor(scaled);
        return floor < -CoordinateLimit ? -CoordinateLimit : floor > CoordinateLimit ? CoordinateLimit : (long)floor;
    }

    private static long PackCell(long x, long y, long z) =>
        ((x + (1L << 20)) << 42) | ((y + (1L << 20)) << 21) | (z + (1L << 20));

    private static void UnpackCell(long cell, out long x, out long y, out long z)
    {
        const long mask = (1L << 21) - 1;
        x = ((cell >> 42) & mask) - (1L << 20);
        y = ((cell >> 21) & mask) - (1L << 20);
        z = (cell & mask) - (1L << 20);
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private int Bucket(long cell)
    {
        // Fibonacci hashing of the packed cell: the high bits of cell * 2^64 / phi.
        var hash = unchecked((ulong)cell * 0x9E3779B97F4A7C15UL);
        return (int)(hash >> 40) & _mask;
    }
}
