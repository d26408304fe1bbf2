using System;
using System.Runtime.CompilerServices;

namespace ParticlePhysics.Contacts;

/// <summary>
/// Where <see cref="SpatialHashGrid"/> keeps each cell: a bucket of a dense box of cells when the occupied cells' bounding
/// box is small (at most <see cref="DenseFactor"/> cells per box), or of a hash table of 2^k &gt;= 2 N buckets otherwise.
/// </summary>
/// <remarks>
/// <para>
/// Dense: the bounding box of the occupied cells, n_x n_y n_z cells, is numbered axis after axis, the axis with the
/// fewest cells fastest and the one with the most slowest (ties in x, y, z order): bucket = (c_f - lo_f) + n_f ((c_m -
/// lo_m) + n_m (c_s - lo_s)). Each bucket is one cell, so buckets in order are cells in order, neighbouring cells are
/// near each other in the table, and a cell outside the box has no bucket (-1). Numbering the shortest axis fastest
/// keeps the cells of a slab of the slowest axis, n_f n_m of them, as few as the box allows: a pile of three layers
/// numbers its height fastest, a cloth lying flat its thickness.
/// </para>
/// <para>
/// Hashed (the cells are spread thinly: a few far-apart particles, a cloth draped in 3-D): Fibonacci hashing of the
/// packed cell, the high bits of cell * 2^64 / phi, which scatters any regular pattern of cells evenly over the table;
/// cells that share a bucket are told apart by the grid.
/// </para>
/// </remarks>
internal struct CellBuckets
{
    /// <summary>The most cells per box for which the table is dense.</summary>
    public const int DenseFactor = 4;

    /// <summary>The values <see cref="ForwardOffsets"/> writes: the cell itself and the 13 after it, 3 steps each.</summary>
    public const int ForwardLength = 42;

    // Cell coordinates are clamped to 21 bits each (+-1,048,574 cells) so that three pack into one long; clamping
    // merges far cells, which costs time, never a pair (the distance or overlap test decides).
    private const long CoordinateLimit = (1L << 20) - 2;

    // The cell itself, then the 13 neighbours that come after it in lexicographic order, as steps along the slowest,
    // the middle and the fastest axis of the table's numbering (Axis).
    private static readonly int[] _forward =
    {
        0, 0, 0, 0, 0, 1, 0, 1, -1, 0, 1, 0, 0, 1, 1, 1, -1, -1, 1, -1, 0, 1, -1, 1, 1, 0, -1, 1, 0, 0, 1, 0, 1, 1, 1, -1,
        1, 1, 0, 1, 1, 1,
    };

    private long _x0, _y0, _z0, _nx, _ny, _nz, _sx, _sy, _sz;
    private int _mask, _fast, _middle, _slow;

    /// <summary>True when each bucket is one cell of the box.</summary>
    public bool Dense { get; private set; }

    /// <summary>The number of buckets.</summary>
    public int Count { get; private set; }

    /// <summary>
    /// The axis (0: x, 1: y, 2: z) the numbering runs along at rank 0 (fastest), 1 or 2 (slowest): x, y, z slowest
    /// to fastest for a hashed table.
    /// </summary>
    public readonly int Axis(int rank) => rank == 0 ? _fast : rank == 1 ? _middle : _slow;

    /// <summary>The most buckets <see cref="Fit"/> chooses for <paramref name="boxes"/> boxes: the size of a table that fits any of them.</summary>
    public static int Capacity(int boxes) => Math.Max(DenseFactor * boxes, HashedCount(boxes));

    /// <summary>
    /// Chooses the table for <paramref name="boxes"/> boxes whose cells span [lo, hi] on each axis (cell coordinates,
    /// within +-2^20; ignored when there are no boxes).
    /// </summary>
    public void Fit(long loX, long loY, long loZ, long hiX, long hiY, long hiZ, int boxes)
    {
        var limit = DenseFactor * (long)boxes;
        var (nx, ny, nz) = boxes > 0 ? (hiX - loX + 1, hiY - loY + 1, hiZ - loZ + 1) : (0L, 0L, 0L);
        Dense = boxes > 0 && nx <= limit && ny <= limit && nx * ny <= limit && nx * ny * nz <= limit;
        if (!Dense)
        {
            Count = HashedCount(boxes);
            _mask = Count - 1;
            (_fast, _middle, _slow) = (2, 1, 0);
            return;
        }

        (_x0, _y0, _z0, _nx, _ny, _nz) = (loX, loY, loZ, nx, ny, nz);
        Count = (int)(nx * ny * nz);

        // Strides: the axes sorted by their number of cells (a three-element sorting network; ties keep x, y, z order),
        // the first 1, the second n_first, the third n_first n_second.
        Span<long> n = stackalloc long[] { nx, ny, nz };
        Span<int> axes = stackalloc int[] { 0, 1, 2 };
        Order(n, axes, 0, 1);
        Order(n, axes, 1, 2);
        Order(n, axes, 0, 1);
        Span<long> strides = stackalloc long[3];
        strides[axes[0]] = 1;
        strides[axes[1]] = n[axes[0]];
        strides[axes[2]] = n[axes[0]] * n[axes[1]];
        (_sx, _sy, _sz) = (strides[0], strides[1], strides[2]);
        (_fast, _middle, _slow) = (axes[0], axes[1], axes[2]);
    }

    /// <summary>The bucket of cell (x, y, z), whose packed form is <paramref name="packed"/>; -1 when it has none.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public readonly int Of(long x, long y, long z, long packed)
    {
        if (!Dense)
        {
            var hash = unchecked((ulong)packed * 0x9E3779B97F4A7C15UL);
            return (int)(hash >> 40) & _mask;
        }

        // One unsigned comparison per axis tests 0 <= c - lo < n.
        ulong dx = unchecked((ulong)(x - _x0)), dy = unchecked((ulong)(y - _y0)), dz = unchecked((ulong)(z - _z0));
        if (dx >= (ulong)_nx || dy >= (ulong)_ny || dz >= (ulong)_nz)
        {
            return -1;
        }

        return (int)(((long)dx * _sx) + ((long)dy * _sy) + ((long)dz * _sz));
    }

    /// <summary>
    /// Writes into <paramref name="offsets"/> (<see cref="ForwardLength"/> values) the cell itself and the 13 cells after
    /// it as (dx, dy, dz) steps in the last <see cref="Fit"/>'s numbering, so that a dense table's cells meet their
    /// neighbours only after them (a hashed table keeps x, y, z): visiting these from every cell reads each pair of
    /// neighbouring cells once.
    /// </summary>
    public readonly void ForwardOffsets(int[] offsets)
    {
        for (var k = 0; k < 14; k++)
        {
            for (var rank = 0; rank < 3; rank++)
            {
                offsets[(3 * k) + Axis(rank)] = _forward[(3 * k) + 2 - rank];
            }
        }
    }

    /// <summary>The cell coordinate of a position over the cell size, floor(scaled), clamped to +-(2^20 - 2) (NaN too).</summary>
    public static long Coordinate(double scaled)
    {
        var floor = Math.Floor(scaled);
        return floor > CoordinateLimit ? CoordinateLimit : floor >= -CoordinateLimit ? (long)floor : -CoordinateLimit;
    }

    /// <summary>Cell (x, y, z), each within +-2^20, packed into one long (21 bits each).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static long Pack(long x, long y, long z) =>
        ((x + (1L << 20)) << 42) | ((y + (1L << 20)) << 21) | (z + (1L << 20));

    /// <summary>The cell <see cref="Pack"/> packed.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void Unpack(long cell, out long x, out long y, out long z)
    {
        const long mask = (1L << 21) - 1;
        x = ((cell >> 42) & mask) - (1L << 20);
        y = ((cell >> 21) & mask) - (1L << 20);
        z = (cell & mask) - (1L << 20);
    }

    private static void Order(Span<long> n, Span<int> axes, int a, int b)
    {
        if (n[axes[b]] < n[axes[a]])
        {
            (axes[a], axes[b]) = (axes[b], axes[a]);
        }
    }

    private static int HashedCount(int boxes)
    {
        var count = 2;
        while (count < 2 * boxes)
        {
            count *= 2;
        }

        return count;
    }
}
