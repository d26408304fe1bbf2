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
/// adjacent cells: each box looks at its own cell and 13 of the 26 around it (those after it in the lexicographic order
/// of the table's numbering, slowest axis first), so that each pair of neighbouring cells is visited once. The cells
/// are kept in buckets (<see cref="CellBuckets"/>: a dense box of cells when the occupied cells fill one, a hash table
/// otherwise), and the boxes are counting-sorted by bucket into slots (stable: a bucket's boxes in index order), each
/// slot holding its box's bounds and cell, so that the boxes of a cell and of the cells beside it are read from
/// consecutive memory; a box found in a bucket is a neighbour only if its own cell is the one visited, so hash
/// collisions neither duplicate nor invent pairs. The few larger boxes (a particle moving very fast) are tested against
/// every box.
/// </para>
/// <para>
/// Each overlapping pair is reported once, as (i, j) with i &lt; j, in a deterministic order: with a dense table, in
/// the order of the cells (a box's pairs with the boxes of its own and its 13 cells, then the next box's), so that
/// the pairs of neighbouring particles come close together in the list wherever the particles are stored, and the
/// stages that walk the pairs read each particle's data a few times in quick succession rather than at times a layer
/// of a pile apart; with a hashed table (cells spread thinly), in the order of the boxes' indices. The large boxes'
/// pairs come last.
/// </para>
/// </remarks>
public sealed class SpatialHashGrid
{
    /// <summary>
    /// The most pairs one <see cref="FindPairs"/> reports: 2^26 (67,108,864; 512 MB for the list). Boxes heaped on
    /// each other (10,000 at one point make 50 million pairs) can make more pairs than a program can hold; past this
    /// the search stops and throws instead.
    /// </summary>
    public const int MaxPairs = 1 << 26;

    private const int LargeFactor = 4;

    private readonly int[] _offsets = new int[CellBuckets.ForwardLength]; // the last build's forward cells (CellBuckets.ForwardOffsets)
    private double[] _slotMin = Array.Empty<double>();
    private double[] _slotMax = Array.Empty<double>();
    private long[] _slotCell = Array.Empty<long>();
    private int[] _boxOf = Array.Empty<int>();
    private int[] _slotOf = Array.Empty<int>();
    private long[] _cellOf = Array.Empty<long>();
    private int[] _bucketOf = Array.Empty<int>();
    private int[] _bucketStart = Array.Empty<int>();
    private int[] _first = Array.Empty<int>();
    private int[] _second = Array.Empty<int>();
    private CellBuckets _buckets;
    private int _ordinaryCount;
    private int _largeCount;
    private int _pairCount;
    private int _pairLimit;
    private double _cellSize;

    /// <summary>The number of pairs the last <see cref="FindPairs"/> found.</summary>
    public int PairCount => _pairCount;

    /// <summary>The first (smaller) index of each pair the last <see cref="FindPairs"/> found.</summary>
    public ReadOnlySpan<int> First => _first.AsSpan(0, _pairCount);

    /// <summary>The second (larger) index of each pair.</summary>
    public ReadOnlySpan<int> Second => _second.AsSpan(0, _pairCount);

    /// <summary>The cell size of the last build, in metres.</summary>
    public double CellSize => _cellSize;

    /// <summary>True when the last build kept the cells in a dense box (the pairs then come in the order of the cells).</summary>
    internal bool Dense => _buckets.Dense;

    /// <summary>
    /// Finds every pair of overlapping boxes (touching counts) among <paramref name="count"/> boxes, box i being
    /// [min[3i..3i+2], max[3i..3i+2]]; <paramref name="filter"/>, if not null, drops pairs it refuses.
    /// </summary>
    /// <exception cref="InvalidOperationException">More than <see cref="MaxPairs"/> pairs overlap.</exception>
    public void FindPairs(ReadOnlySpan<double> min, ReadOnlySpan<double> max, int count, IContactPairFilter? filter = null)
    {
        if (!TryFindPairs(min, max, count, filter, MaxPairs))
        {
            throw new InvalidOperationException(
                $"More than {MaxPairs} pairs of the {count} boxes overlap (SpatialHashGrid.MaxPairs): too many to list.");
        }
    }

    /// <summary>
    /// The same with a limit of at most <see cref="MaxPairs"/> pairs: false, with the pairs found so far, once more
    /// would have to be listed (the list never grows past the limit).
    /// </summary>
    internal bool TryFindPairs(ReadOnlySpan<double> min, ReadOnlySpan<double> max, int count, IContactPairFilter? filter, int limit) =>
        TryFindPairs(min, max, count, filter, limit, null);

    /// <summary>
    /// The same, where <paramref name="still"/> (if not null) marks boxes that need no pair with each other (sleeping
    /// particles): a still box is not visited, and each box that is visits all 26 neighbouring cells for still boxes
    /// (the 13 of the forward half for the others, as before), so the work follows the boxes that move.
    /// </summary>
    internal bool TryFindPairs(ReadOnlySpan<double> min, ReadOnlySpan<double> max, int count, IContactPairFilter? filter, int limit, bool[]? still)
    {
        if (count < 0 || min.Length < 3 * count || max.Length < 3 * count)
        {
            throw new ArgumentException($"min and max need 3 values for each of the {count} boxes.", nameof(count));
        }

        Build(min.ForReading(), max.ForReading(), count);
        _pairCount = 0;
        _pairLimit = Math.Min(limit, MaxPairs);

        // The ordinary boxes in slot order (the cells' order) when the table is dense, else in index order.
        var visits = _buckets.Dense ? _ordinaryCount : count;
        for (var v = 0; v < visits; v++)
        {
            var slot = _buckets.Dense ? v : _slotOf[v];
            if (slot >= _ordinaryCount)
            {
                continue; // a large box: paired below
            }

            var i = _boxOf[slot];
            if (still is not null && still[i])
            {
                continue; // its pairs with moving boxes are found from them
            }

            CellBuckets.Unpack(_slotCell[slot], out var cx, out var cy, out var cz);
            var offsets = still is null ? 14 : 27;
            for (var offset = 0; offset < offsets; offset++)
            {
                // Its own cell (later boxes only, and still ones), then the 13 neighbours of the forward half (each
                // pair of cells once), then with still boxes the 13 of the backward half for those alone.
                var forward = offset < 14;
                var sign = forward ? 1 : -1;
                var k = forward ? offset : offset - 13;
                long x = cx + (sign * _offsets[3 * k]), y = cy + (sign * _offsets[(3 * k) + 1]), z = cz + (sign * _offsets[(3 * k) + 2]);
                var cell = CellBuckets.Pack(x, y, z);
                var bucket = _buckets.Of(x, y, z, cell);
                if (bucket < 0)
                {
                    continue; // outside the dense box: no box there
                }

                for (var q = _bucketStart[bucket]; q < _bucketStart[bucket + 1]; q++)
                {
                    var j = _boxOf[q];
                    var jStill = still is not null && still[j];
                    if ((forward ? offset > 0 || j > i || jStill : jStill) && _slotCell[q] == cell && Overlap(slot, q)
                        && !Emit(Math.Min(i, j), Math.Max(i, j), filter))
                    {
                        return false;
                    }
                }
            }
        }

        for (var l = 0; l < _largeCount; l++)
        {
            var slot = _ordinaryCount + l;
            var i = _boxOf[slot];
            for (var j = 0; j < count; j++)
            {
                // Against every ordinary box, and against the large boxes after it (each such pair once).
                if (j != i && (_slotOf[j] < _ordinaryCount || j > i) && !(still is not null && still[i] && still[j]) && Overlap(slot, _slotOf[j])
                    && !Emit(Math.Min(i, j), Math.Max(i, j), filter))
                {
                    return false;
                }
            }
        }

        return true;
    }

    /// <summary>
    /// The cell size, each ordinary box's cell, the table (<see cref="CellBuckets"/>), and the slots: the ordinary boxes
    /// counting-sorted by bucket, then the large ones in index order.
    /// </summary>
    private void Build(Span<double> min, Span<double> max, int count)
    {
        if (_slotOf.Length < count)
        {
            _slotMin = new double[3 * count];
            _slotMax = new double[3 * count];
            _slotCell = new long[count];
            _boxOf = new int[count];
            _slotOf = new int[count];
            _cellOf = new long[count];
            _bucketOf = new int[count];
        }

        if (_bucketStart.Length < CellBuckets.Capacity(count) + 1)
        {
            _bucketStart = new int[CellBuckets.Capacity(count) + 1];
        }

        var sum = 0.0;
        for (var i = 0; i < count; i++)
        {
            sum += Extent(min, max, i);
        }

        var limit = count == 0 ? 0.0 : LargeFactor * sum / count;
        var cell = 0.0;
        for (var i = 0; i < count; i++)
        {
            var extent = Extent(min, max, i);
            if (extent <= limit)
            {
                cell = Math.Max(cell, extent);
            }
        }

        _cellSize = cell > 0.0 ? cell : 1.0;
        var inverse = 1.0 / _cellSize;
        _ordinaryCount = 0;
        _largeCount = 0;
        long loX = long.MaxValue, loY = long.MaxValue, loZ = long.MaxValue;
        long hiX = long.MinValue, hiY = long.MinValue, hiZ = long.MinValue;
        for (var i = 0; i < count; i++)
        {
            if (Extent(min, max, i) > limit)
            {
                _bucketOf[i] = -1;
                _largeCount++;
                continue;
            }

            var o = 3 * i;
            var x = CellBuckets.Coordinate(0.5 * (min[o] + max[o]) * inverse);
            var y = CellBuckets.Coordinate(0.5 * (min[o + 1] + max[o + 1]) * inverse);
            var z = CellBuckets.Coordinate(0.5 * (min[o + 2] + max[o + 2]) * inverse);
            (loX, loY, loZ) = (Math.Min(loX, x), Math.Min(loY, y), Math.Min(loZ, z));
            (hiX, hiY, hiZ) = (Math.Max(hiX, x), Math.Max(hiY, y), Math.Max(hiZ, z));
            _cellOf[i] = CellBuckets.Pack(x, y, z);
            _bucketOf[i] = 0;
            _ordinaryCount++;
        }

        _buckets.Fit(loX, loY, loZ, hiX, hiY, hiZ, _ordinaryCount);
        _buckets.ForwardOffsets(_offsets);

        var buckets = _buckets.Count;
        Array.Clear(_bucketStart, 0, buckets + 1);
        for (var i = 0; i < count; i++)
        {
            if (_bucketOf[i] >= 0)
            {
                CellBuckets.Unpack(_cellOf[i], out var x, out var y, out var z);
                var bucket = _buckets.Of(x, y, z, _cellOf[i]);
                _bucketOf[i] = bucket;
                _bucketStart[bucket + 1]++;
            }
        }

        for (var b = 0; b < buckets; b++)
        {
            _bucketStart[b + 1] += _bucketStart[b];
        }

        // Counting sort by bucket: a second pass places each box after those of lower index in its bucket; the large
        // boxes take the slots after the ordinary ones. Each slot gets a copy of its box.
        var large = _ordinaryCount;
        for (var i = 0; i < count; i++)
        {
            var bucket = _bucketOf[i];
            var slot = bucket >= 0 ? _bucketStart[bucket]++ : large++;
            _boxOf[slot] = i;
            _slotOf[i] = slot;
            _slotCell[slot] = bucket >= 0 ? _cellOf[i] : 0;
            for (var c = 0; c < 3; c++)
            {
                _slotMin[(3 * slot) + c] = min[(3 * i) + c];
                _slotMax[(3 * slot) + c] = max[(3 * i) + c];
            }
        }

        for (var b = buckets; b > 0; b--)
        {
            _bucketStart[b] = _bucketStart[b - 1];
        }

        _bucketStart[0] = 0;
    }

    /// <summary>Lists the pair (i, j) unless the filter refuses it; false when the list is at its limit.</summary>
    private bool Emit(int i, int j, IContactPairFilter? filter)
    {
        if (filter is not null && !filter.MayCollide(i, j))
        {
            return true;
        }

        if (_pairCount >= _pairLimit)
        {
            return false;
        }

        if (_pairCount == _first.Length)
        {
            var capacity = (int)Math.Min(_pairLimit, Math.Max(64L, 2L * _first.Length));
            Array.Resize(ref _first, capacity);
            Array.Resize(ref _second, capacity);
        }

        _first[_pairCount] = i;
        _second[_pairCount] = j;
        _pairCount++;
        return true;
    }

    /// <summary>Whether the boxes in slots <paramref name="a"/> and <paramref name="b"/> overlap.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private bool Overlap(int a, int b)
    {
        a *= 3;
        b *= 3;
        return _slotMin[a] <= _slotMax[b] && _slotMin[b] <= _slotMax[a]
            && _slotMin[a + 1] <= _slotMax[b + 1] && _slotMin[b + 1] <= _slotMax[a + 1]
            && _slotMin[a + 2] <= _slotMax[b + 2] && _slotMin[b + 2] <= _slotMax[a + 2];
    }

    private static double Extent(Span<double> min, Span<double> max, int i)
    {
        var o = 3 * i;
        return Math.Max(max[o] - min[o], Math.Max(max[o + 1] - min[o + 1], max[o + 2] - min[o + 2]));
    }
}
