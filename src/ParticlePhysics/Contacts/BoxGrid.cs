using System;

namespace ParticlePhysics.Contacts;

/// <summary>
/// A hash grid of boxes (a cloth's triangles or edges, each grown by the thickness): each box is listed in every cell
/// it covers, so that a small query box visits only the few cells it covers and meets each listed box once.
/// </summary>
/// <remarks>
/// Once: a box is met in the cell that holds the low corner of its overlap with the query box, which both cover, and
/// skipped in every other cell (and in cells that only share a hash bucket with it). Built by a counting sort over
/// the buckets, items in index order within a bucket, so queries meet items in the same order on every runtime. The
/// arrays grow when a build needs more entries than they hold, and are kept: a settled cloth builds without
/// allocating.
/// </remarks>
internal sealed class BoxGrid
{
    /// <summary>The most cell entries one build may list (a bound on its work and memory).</summary>
    public const int MaxEntries = 1 << 26;

    private int[] _start = new int[17];
    private int[] _items = Array.Empty<int>();
    private int[] _entryBucket = Array.Empty<int>();
    private int[] _entryItem = Array.Empty<int>();
    private double[] _boxes = Array.Empty<double>();
    private double _inverseCell;
    private int _count;

    /// <summary>Starts a build of <paramref name="count"/> boxes in cells of size <paramref name="cell"/>.</summary>
    public void Begin(int count, double cell)
    {
        _count = count;
        _inverseCell = 1.0 / cell;
        if (_boxes.Length < 6 * count)
        {
            _boxes = new double[6 * count];
        }

        var buckets = 16;
        while (buckets < 2 * count)
        {
            buckets *= 2;
        }

        if (_start.Length < buckets + 1)
        {
            _start = new int[buckets + 1];
        }
    }

    /// <summary>Sets box <paramref name="item"/> (during a build).</summary>
    public void Set(int item, Vector3d low, Vector3d high)
    {
        var o = 6 * item;
        _boxes[o] = low.X;
        _boxes[o + 1] = low.Y;
        _boxes[o + 2] = low.Z;
        _boxes[o + 3] = high.X;
        _boxes[o + 4] = high.Y;
        _boxes[o + 5] = high.Z;
    }

    /// <summary>Lists every box in the cells it covers; the build is then ready for queries.</summary>
    public void End()
    {
        long counted = 0;
        for (var i = 0; i < _count; i++)
        {
            var o = 6 * i;
            counted += (long)(Cell(_boxes[o + 3]) - Cell(_boxes[o]) + 1) * (Cell(_boxes[o + 4]) - Cell(_boxes[o + 1]) + 1) * (Cell(_boxes[o + 5]) - Cell(_boxes[o + 2]) + 1);
        }

        if (counted > MaxEntries)
        {
            throw new InvalidOperationException(
                $"Self-collision: the cloth's boxes cover {counted} grid cells, more than the {MaxEntries} allowed; the cloth is spread over far more than its size (it may have diverged).");
        }

        var entries = (int)counted;

        if (_entryItem.Length < entries)
        {
            var size = Math.Max(entries, 2 * _entryItem.Length);
            _entryItem = new int[size];
            _entryBucket = new int[size];
            _items = new int[size];
        }

        var mask = _start.Length - 2;
        Array.Clear(_start, 0, _start.Length);
        var e = 0;
        for (var i = 0; i < _count; i++)
        {
            var o = 6 * i;
            int x1 = Cell(_boxes[o + 3]), y0 = Cell(_boxes[o + 1]), y1 = Cell(_boxes[o + 4]), z0 = Cell(_boxes[o + 2]), z1 = Cell(_boxes[o + 5]);
            for (var cx = Cell(_boxes[o]); cx <= x1; cx++)
            {
                for (var cy = y0; cy <= y1; cy++)
                {
                    for (var cz = z0; cz <= z1; cz++)
                    {
                        var bucket = Hash(cx, cy, cz) & mask;
                        _entryBucket[e] = bucket;
                        _entryItem[e++] = i;
                        _start[bucket + 1]++;
                    }
                }
            }
        }

        var buckets = _start.Length - 1;
        for (var b = 0; b < buckets; b++)
        {
            _start[b + 1] += _start[b];
        }

        // Filled from the back, each bucket's end moves down to its first entry, which then sits one place up.
        for (var k = e - 1; k >= 0; k--)
        {
            _items[--_start[_entryBucket[k] + 1]] = _entryItem[k];
        }

        for (var b = 0; b < buckets; b++)
        {
            _start[b] = _start[b + 1];
        }

        _start[buckets] = e;
    }

    /// <summary>
    /// The boxes that overlap the query box (low, high), each once: cell by cell (x, then y, then z), in index order
    /// within a cell.
    /// </summary>
    public Query Overlapping(Vector3d low, Vector3d high) => new(this, low, high);

    /// <summary>An enumeration of <see cref="Overlapping"/>; allocation-free (a ref struct over the grid's arrays).</summary>
    public ref struct Query
    {
        private readonly BoxGrid _grid;
        private readonly Vector3d _low;
        private readonly Vector3d _high;
        private readonly int _x1;
        private readonly int _y0;
        private readonly int _y1;
        private readonly int _z0;
        private readonly int _z1;
        private int _cx;
        private int _cy;
        private int _cz;
        private int _entry;
        private int _end;

        internal Query(BoxGrid grid, Vector3d low, Vector3d high)
        {
            _grid = grid;
            _low = low;
            _high = high;
            _cx = grid.Cell(low.X);
            _x1 = grid.Cell(high.X);
            _y0 = grid.Cell(low.Y);
            _y1 = grid.Cell(high.Y);
            _z0 = grid.Cell(low.Z);
            _z1 = grid.Cell(high.Z);
            _cy = _y0;
            _cz = _z0 - 1; // MoveNext steps to the first cell
            _entry = 0;
            _end = 0;
            Current = -1;
        }

        /// <summary>The item met.</summary>
        public int Current { get; private set; }

        /// <summary>For <c>foreach</c>.</summary>
        public Query GetEnumerator() => this;

        /// <summary>Steps to the next overlapping box; false when there is none.</summary>
        public bool MoveNext()
        {
            while (true)
            {
                while (_entry < _end)
                {
                    var item = _grid._items[_entry++];
                    if (_grid.MeetsHere(item, _low, _high, _cx, _cy, _cz))
                    {
                        Current = item;
                        return true;
                    }
                }

                if (++_cz > _z1)
                {
                    _cz = _z0;
                    if (++_cy > _y1)
                    {
                        _cy = _y0;
                        if (++_cx > _x1)
                        {
                            return false;
                        }
                    }
                }

                var bucket = Hash(_cx, _cy, _cz) & (_grid._start.Length - 2);
                _entry = _grid._start[bucket];
                _end = _grid._start[bucket + 1];
            }
        }
    }

    // Whether item's box overlaps the query box and cell (cx, cy, cz) is the one to meet it in.
    private bool MeetsHere(int item, Vector3d low, Vector3d high, int cx, int cy, int cz)
    {
        var o = 6 * item;
        double lx = _boxes[o], ly = _boxes[o + 1], lz = _boxes[o + 2];
        if (lx > high.X || ly > high.Y || lz > high.Z || _boxes[o + 3] < low.X || _boxes[o + 4] < low.Y || _boxes[o + 5] < low.Z)
        {
            return false;
        }

        return Cell(lx > low.X ? lx : low.X) == cx && Cell(ly > low.Y ? ly : low.Y) == cy && Cell(lz > low.Z ? lz : low.Z) == cz;
    }

    private int Cell(double coordinate)
    {
        var scaled = coordinate * _inverseCell;
        return scaled >= 1e9 ? 1_000_000_000 : scaled <= -1e9 ? -1_000_000_000 : (int)Math.Floor(scaled);
    }

    private static int Hash(int x, int y, int z) => unchecked((x * 73856093) ^ (y * 19349663) ^ (z * 83492791)) & int.MaxValue;
}
