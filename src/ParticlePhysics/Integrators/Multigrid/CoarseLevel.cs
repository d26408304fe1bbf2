using System;
using System.Numerics;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Integrators.Multigrid;

/// <summary>
/// One coarse level: diagonal and off-diagonal 3 x 3 blocks (compressed rows with both directions of every pair in
/// its sparsity, columns increasing; each pair's block stored once), the inverted diagonal, the right-hand side B
/// and solution X of its cycle, and its link to the next. Its passes are classes of their own
/// (<see cref="BlockInversionPass"/>, <see cref="CoarseGalerkinPass"/>, <see cref="ResidualRestrictionPass"/>,
/// <see cref="PostSmoothingPass"/>); the rows they apply are in CoarseLevel.Rows.cs.
/// </summary>
/// <remarks>
/// The operator is symmetric, A_ji = A_ij^T, so each pair's block is stored once, in the row of the smaller
/// aggregate (the upper triangle, in row order: a row's upper blocks lie together), and a row reads the blocks
/// left of its diagonal transposed from the rows above it. A sweep streams half the bytes it would with both
/// directions stored, and the rows it re-reads were read a few rows earlier, so they are still in the cache.
/// </remarks>
internal sealed unsafe partial class CoarseLevel
{
    // Below this many rows a level's passes stay on the calling thread: waking the workers would cost more than the
    // pass (on the 64 x 64 cloth the levels of 1024 and 256 aggregates share their passes, those of 64 and 16 do not).
    private const int ParallelRows = 256;

    private readonly int[] _rowStart;
    private readonly int[] _column;
    private readonly int[] _split;     // per row: its first entry right of the diagonal (columns are increasing)
    private readonly int[] _slot;      // per entry: its stored block, counted after the diagonal ones
    private readonly int[] _upperStart; // per row, and one past the last: its first stored off-diagonal block
    private double[] _smoothed; // where a post-smoothing writes the new X (the rows still to come read the old one)

    // The lanes path (Lanes): each row's blocks in row order, the diagonal first, each 3 x 3 block by columns, so
    // that a block times a vector is three column vectors scaled and added, four lanes at a time (the fourth
    // unused); and the inverted diagonal blocks by columns. Rewritten from Values and Inverse at every inversion.
    private readonly double[] _laneBlocks = Array.Empty<double>();
    private readonly double[] _laneInverse = Array.Empty<double>();
    private int[] _nextAggregate = Array.Empty<int>();
    private int[] _nextMemberStart = Array.Empty<int>();
    private int[] _nextMembers = Array.Empty<int>();
    private int[] _nextTarget = Array.Empty<int>();

    public CoarseLevel(CouplingGraph graph)
    {
        Count = graph.Count;
        _rowStart = graph.RowStart;
        _column = graph.Column;
        (_split, _slot, _upperStart) = UpperSlots(Count, _rowStart, _column);
        Values = new double[9 * (Count + _upperStart[Count])];
        Inverse = new double[9 * Count];

        // One value past the rows: the lanes path reads a row's B and X as four values (the fourth unused).
        B = new double[(3 * Count) + 1];
        X = new double[(3 * Count) + 1];
        _smoothed = new double[(3 * Count) + 1];
        if (Lanes)
        {
            _laneBlocks = new double[(9 * (Count + _column.Length)) + 1];
            _laneInverse = new double[(9 * Count) + 1];
        }
    }

    /// <summary>
    /// Whether the sweeps take a row's three components as lanes of one System.Numerics.Vector (CoreCLR with
    /// 256-bit vectors: four lanes of double), else one at a time (Mono, IL2CPP, other widths). Per lane the
    /// same multiplications, additions and subtractions in the same order, so the same bits.
    /// </summary>
    public static bool Lanes => Vector.IsHardwareAccelerated && Vector<double>.Count == 4;

    public int Count { get; }

    /// <summary>
    /// The blocks: the diagonal ones (block i for row i), then each pair's off-diagonal block A_ij with i &lt; j once
    /// (block Count + slot of entry k; the entry (j, i) reads it transposed).
    /// </summary>
    public double[] Values { get; }

    /// <summary>The inverted diagonal blocks D^-1, row-major (<see cref="BlockInversionPass"/>).</summary>
    public double[] Inverse { get; }

    public double[] B { get; }

    public double[] X { get; private set; }

    /// <summary>The buffer a post-smoothing writes into; <see cref="SwapSmoothed"/> makes it <see cref="X"/>.</summary>
    public double[] Smoothed => _smoothed;

    /// <summary>Per row, and one past the last: its first entry in <see cref="Column"/>.</summary>
    public int[] RowStart => _rowStart;

    /// <summary>Per entry: its column, increasing along a row.</summary>
    public int[] Column => _column;

    /// <summary>Per row: its first entry right of the diagonal.</summary>
    public int[] Split => _split;

    /// <summary>Per entry: its stored off-diagonal block, block Count + slot of <see cref="Values"/>.</summary>
    public int[] Slot => _slot;

    /// <summary>The lanes path's copy of each row's blocks by columns, the diagonal first (empty without lanes).</summary>
    public double[] LaneBlocks => _laneBlocks;

    /// <summary>The lanes path's copy of the inverted diagonal blocks by columns (empty without lanes).</summary>
    public double[] LaneInverse => _laneInverse;

    /// <summary>The map of this level's rows into the next level's aggregates (empty on the coarsest).</summary>
    public int[] NextAggregate => _nextAggregate;

    /// <summary>Per aggregate of the next level, and one past the last: its first member in <see cref="NextMembers"/>.</summary>
    public int[] NextMemberStart => _nextMemberStart;

    /// <summary>The members (rows of this level) of each aggregate of the next level, in increasing order.</summary>
    public int[] NextMembers => _nextMembers;

    /// <summary>Per entry: the next level's stored block it adds into (<see cref="Target"/>), -1 for none.</summary>
    public int[] NextTarget => _nextTarget;

    /// <summary>The runner for this level's passes: none below <see cref="ParallelRows"/> rows.</summary>
    public IParallelRunner? RunnerFor(IParallelRunner? runner) => Count >= ParallelRows ? runner : null;

    /// <summary>True when block <paramref name="target"/> of <see cref="Values"/> lies in rows [begin, end).</summary>
    public bool InRows(int target, int begin, int end) =>
        target < Count ? target >= begin && target < end : target - Count >= _upperStart[begin] && target - Count < _upperStart[end];

    /// <summary>The diagonal blocks of rows [begin, end) in <see cref="Values"/>.</summary>
    public (int First, int Last) BlockRange(int begin, int end) => (begin, end);

    /// <summary>The off-diagonal blocks stored in rows [begin, end) of <see cref="Values"/>.</summary>
    public (int First, int Last) OffDiagonalRange(int begin, int end) => (Count + _upperStart[begin], Count + _upperStart[end]);

    /// <summary>
    /// The index in <see cref="Values"/> of block (row, column) when it is stored as it is: the diagonal, or
    /// row &lt; column; -1 for row &gt; column, whose block is the transpose of (column, row).
    /// </summary>
    public int Target(int row, int column)
    {
        if (row == column)
        {
            return row;
        }

        if (row > column)
        {
            return -1;
        }

        return Count + _slot[Entry(_rowStart, _column, row, column)];
    }

    /// <summary>The entry of (row, column) in compressed rows with increasing columns.</summary>
    private static int Entry(int[] rowStart, int[] column, int row, int col)
    {
        var k = Array.BinarySearch(column, rowStart[row], rowStart[row + 1] - rowStart[row], col);
        if (k < 0)
        {
            throw new InvalidOperationException($"No coarse block ({row}, {col}): the aggregation is inconsistent.");
        }

        return k;
    }

    /// <summary>
    /// Numbers the entries right of the diagonal in row order (the stored blocks) and gives each entry left of it
    /// the number of its mirror (j, i); the graph is symmetric (every pair in both rows).
    /// </summary>
    private static (int[] Split, int[] Slot, int[] UpperStart) UpperSlots(int count, int[] rowStart, int[] column)
    {
        var split = new int[count];
        var slot = new int[column.Length];
        var upperStart = new int[count + 1];
        var next = 0;
        for (var i = 0; i < count; i++)
        {
            upperStart[i] = next;
            var k = rowStart[i];
            while (k < rowStart[i + 1] && column[k] < i)
            {
                k++;
            }

            split[i] = k;
            for (; k < rowStart[i + 1]; k++)
            {
                slot[k] = next++;
            }
        }

        upperStart[count] = next;
        for (var i = 0; i < count; i++)
        {
            for (var k = rowStart[i]; k < split[i]; k++)
            {
                slot[k] = slot[Entry(rowStart, column, column[k], i)];
            }
        }

        return (split, slot, upperStart);
    }

    public void LinkTo(CoarseLevel next, int[] map)
    {
        _nextAggregate = map;
        (_nextMemberStart, _nextMembers) = CouplingGraph.Members(map, next.Count);
        _nextTarget = new int[_column.Length];
        for (var i = 0; i < Count; i++)
        {
            for (var k = _rowStart[i]; k < _rowStart[i + 1]; k++)
            {
                _nextTarget[k] = next.Target(map[i], map[_column[k]]);
            }
        }
    }

    /// <summary>X += P X_next: each row adds its aggregate's correction from the level below, on the calling thread.</summary>
    public void Prolong(CoarseLevel next)
    {
        fixed (double* x = X, nextX = next.X)
        fixed (int* aggregate = _nextAggregate)
        {
            for (var i = 0; i < Count; i++)
            {
                double* xi = x + (3L * i), ci = nextX + (3L * aggregate[i]);
                xi[0] += ci[0];
                xi[1] += ci[1];
                xi[2] += ci[2];
            }
        }
    }

    /// <summary>Makes the buffer the post-smoothing wrote into this level's X.</summary>
    public void SwapSmoothed() => (X, _smoothed) = (_smoothed, X);

    /// <summary>The operator as a dense row-major matrix, 3 Count values a side (for tests: it allocates).</summary>
    public double[] Dense()
    {
        var n = 3 * Count;
        var a = new double[n * n];
        FillDense(a, n);
        return a;
    }

    /// <summary>Writes the operator into <paramref name="a"/>, dense and row-major with <paramref name="n"/> = 3 Count.</summary>
    public void FillDense(double[] a, int n)
    {
        for (var i = 0; i < Count; i++)
        {
            for (var p = 0; p < 3; p++)
            {
                for (var q = 0; q < 3; q++)
                {
                    a[(((3 * i) + p) * n) + (3 * i) + q] = Values[(9 * i) + (3 * p) + q];
                }
            }

            for (var k = _rowStart[i]; k < _rowStart[i + 1]; k++)
            {
                var j = _column[k];
                var block = 9 * (Count + _slot[k]);
                var transposed = k < _split[i]; // left of the diagonal: the transpose of block (j, i)
                for (var p = 0; p < 3; p++)
                {
                    for (var q = 0; q < 3; q++)
                    {
                        a[(((3 * i) + p) * n) + (3 * j) + q] = Values[block + (transposed ? (3 * q) + p : (3 * p) + q)];
                    }
                }
            }
        }
    }
}
