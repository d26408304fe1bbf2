using System;
using ParticlePhysics.Contacts;

namespace ParticlePhysics.Fluids;

/// <summary>
/// Every pair of points closer than a radius h, for the fluid's kernels: the points are counting-sorted into cells of
/// side h (the contact stage's cell table, <see cref="CellBuckets"/>: dense where the fluid fills its bounding box,
/// hashed where it is spread thin, in a splash), and each point looks at its own cell and the 13 cells after it, so
/// that each pair of neighbouring cells is read once.
/// </summary>
/// <remarks>
/// The contact stage's <see cref="SpatialHashGrid"/> pairs boxes of any size and leaves the distance to its stages;
/// the fluid's points all share one radius, so this search tests the distance itself and lists only the pairs within
/// it, about half of the pairs of boxes of side h that overlap. The pairs come in the order of the cells (a point's
/// pairs with the points of its cell and of the 13 after it, then the next point's): deterministic for given
/// positions, and near each other in memory wherever the particles are stored.
/// </remarks>
internal sealed class FluidNeighbours
{
    private readonly int[] _offsets = new int[CellBuckets.ForwardLength];
    private CellBuckets _buckets;
    private long[] _cellOf = Array.Empty<long>(); // per point
    private int[] _bucketOf = Array.Empty<int>(); // per point
    private int[] _pointOf = Array.Empty<int>(); // per slot
    private double[] _slotX = Array.Empty<double>(); // per slot, 3
    private long[] _slotCell = Array.Empty<long>(); // per slot
    private int[] _bucketStart = Array.Empty<int>();
    private int[] _first = Array.Empty<int>();
    private int[] _second = Array.Empty<int>();
    private int _pairs;

    /// <summary>The number of pairs the last <see cref="Find"/> listed.</summary>
    public int Count => _pairs;

    /// <summary>The first point of each pair.</summary>
    public int[] First => _first;

    /// <summary>The second point of each pair.</summary>
    public int[] Second => _second;

    /// <summary>Lists every pair of the <paramref name="count"/> points <paramref name="x"/> (3 per point) closer than <paramref name="radius"/>.</summary>
    public void Find(double[] x, int count, double radius)
    {
        Sort(x, count, radius);
        _pairs = 0;
        var r2 = radius * radius;
        for (var slot = 0; slot < count; slot++)
        {
            var i = _pointOf[slot];
            double xi = _slotX[3 * slot], yi = _slotX[(3 * slot) + 1], zi = _slotX[(3 * slot) + 2];
            CellBuckets.Unpack(_slotCell[slot], out var cx, out var cy, out var cz);
            for (var k = 0; k < 14; k++)
            {
                long ax = cx + _offsets[3 * k], ay = cy + _offsets[(3 * k) + 1], az = cz + _offsets[(3 * k) + 2];
                var cell = CellBuckets.Pack(ax, ay, az);
                var bucket = _buckets.Of(ax, ay, az, cell);
                if (bucket < 0)
                {
                    continue;
                }

                var start = k == 0 ? slot + 1 : _bucketStart[bucket];
                var end = _bucketStart[bucket + 1];
                for (var q = start; q < end; q++)
                {
                    double dx = _slotX[3 * q] - xi, dy = _slotX[(3 * q) + 1] - yi, dz = _slotX[(3 * q) + 2] - zi;
                    if ((dx * dx) + (dy * dy) + (dz * dz) < r2 && _slotCell[q] == cell)
                    {
                        Emit(i, _pointOf[q]);
                    }
                }
            }
        }
    }

    // Counting-sorts the points by bucket (stable: a bucket's points in index order) into slots.
    private void Sort(double[] x, int count, double radius)
    {
        if (_cellOf.Length < count)
        {
            var capacity = Math.Max(count, 2 * _cellOf.Length);
            _cellOf = new long[capacity];
            _bucketOf = new int[capacity];
            _pointOf = new int[capacity];
            _slotCell = new long[capacity];
            _slotX = new double[3 * capacity];
        }

        if (_bucketStart.Length < CellBuckets.Capacity(count) + 1)
        {
            _bucketStart = new int[CellBuckets.Capacity(count) + 1];
        }

        var inverse = 1.0 / radius;
        long loX = long.MaxValue, loY = long.MaxValue, loZ = long.MaxValue;
        long hiX = long.MinValue, hiY = long.MinValue, hiZ = long.MinValue;
        for (var i = 0; i < count; i++)
        {
            var cx = CellBuckets.Coordinate(x[3 * i] * inverse);
            var cy = CellBuckets.Coordinate(x[(3 * i) + 1] * inverse);
            var cz = CellBuckets.Coordinate(x[(3 * i) + 2] * inverse);
            (loX, loY, loZ) = (Math.Min(loX, cx), Math.Min(loY, cy), Math.Min(loZ, cz));
            (hiX, hiY, hiZ) = (Math.Max(hiX, cx), Math.Max(hiY, cy), Math.Max(hiZ, cz));
            _cellOf[i] = CellBuckets.Pack(cx, cy, cz);
        }

        _buckets.Fit(loX, loY, loZ, hiX, hiY, hiZ, count);
        _buckets.ForwardOffsets(_offsets);

        var buckets = _buckets.Count;
        Array.Clear(_bucketStart, 0, buckets + 1);
        for (var i = 0; i < count; i++)
        {
            CellBuckets.Unpack(_cellOf[i], out var cx, out var cy, out var cz);
            var bucket = _buckets.Of(cx, cy, cz, _cellOf[i]);
            _bucketOf[i] = bucket;
            _bucketStart[bucket + 1]++;
        }

        for (var b = 0; b < buckets; b++)
        {
            _bucketStart[b + 1] += _bucketStart[b];
        }

        for (var i = 0; i < count; i++)
        {
            var slot = _bucketStart[_bucketOf[i]]++;
            _pointOf[slot] = i;
            _slotCell[slot] = _cellOf[i];
            _slotX[3 * slot] = x[3 * i];
            _slotX[(3 * slot) + 1] = x[(3 * i) + 1];
            _slotX[(3 * slot) + 2] = x[(3 * i) + 2];
        }

        for (var b = buckets; b > 0; b--)
        {
            _bucketStart[b] = _bucketStart[b - 1];
        }

        _bucketStart[0] = 0;
    }

    private void Emit(int i, int j)
    {
        if (_pairs == _first.Length)
        {
            var capacity = Math.Max(64, 2 * _pairs);
            Array.Resize(ref _first, capacity);
            Array.Resize(ref _second, capacity);
        }

        _first[_pairs] = i;
        _second[_pairs] = j;
        _pairs++;
    }
}
