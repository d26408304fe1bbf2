using System;
using System.Numerics;
using System.Runtime.CompilerServices;
using ParticlePhysics.Numerics;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Integrators.Multigrid;

/// <summary>
/// One coarse level: diagonal and off-diagonal 3 x 3 blocks (compressed rows with both directions of every pair in
/// its sparsity, columns increasing; each pair's block stored once), the inverted diagonal, the right-hand side B
/// and solution X of its cycle, and its link to the next.
/// </summary>
/// <remarks>
/// The operator is symmetric, A_ji = A_ij^T, so each pair's block is stored once, in the row of the smaller
/// aggregate (the upper triangle, in row order: a row's upper blocks lie together), and a row reads the blocks
/// left of its diagonal transposed from the rows above it. A sweep streams half the bytes it would with both
/// directions stored (level 1 of the 64 x 64 cloth: 295 KB of off-diagonal blocks instead of 590 KB, read twice
/// per iteration), and the rows it re-reads were read a few rows earlier, so they are still in the cache.
/// </remarks>
internal sealed unsafe class CoarseLevel : IParallelWork
{
    private const int ResidualRestrictPass = 0;
    private const int PostSmoothPass = 1;
    private const int InvertPass = 2;
    private const int GalerkinPass = 3;

    // Below this many rows a level's passes stay on the calling thread: waking the workers would cost more. 256: at
    // the runner's 200 us spin limit the workers are awake between the cycle's passes, and on the 64 x 64 cloth
    // (levels of 1024, 256, 64 and 16 aggregates) running level 2 on two threads made the two-thread second 151 ms
    // against 169 ms with 1024 (means of the fastest rounds of four alternating runs of `runner --engine
    // implicit-euler --n 64`). The 64-row level's passes (a few microseconds) stay on the calling thread.
    private const int ParallelRows = 256;

    /// <summary>
    /// Whether the sweeps take a row's three components as lanes of one System.Numerics.Vector (CoreCLR with
    /// 256-bit vectors: four lanes of double), else one at a time (Mono, IL2CPP, other widths). Per lane the
    /// same multiplications, additions and subtractions in the same order, so the same bits.
    /// </summary>
    private static bool Lanes => Vector.IsHardwareAccelerated && Vector<double>.Count == 4;

    private readonly int[] _rowStart;
    private readonly int[] _column;
    private readonly int[] _split;     // per row: its first entry right of the diagonal (columns are increasing)
    private readonly int[] _slot;      // per entry: its stored block, counted after the diagonal ones
    private readonly int[] _upperStart; // per row, and one past the last: its first stored off-diagonal block
    private double[] _smoothed; // where a post-smoothing writes the new X (the rows still to come read the old one)

    // The lanes path (Lanes): each row's blocks in row order, the diagonal first, each 3 x 3 block by columns, so
    // that a block times a vector is three column vectors scaled and added, four lanes at a time (the fourth
    // unused); and the inverted diagonal blocks by columns. Rewritten from Values and Inverse at every Invert.
    private readonly double[] _laneBlocks = Array.Empty<double>();
    private readonly double[] _laneInverse = Array.Empty<double>();
    private int[] _nextAggregate = Array.Empty<int>();
    private int[] _nextMemberStart = Array.Empty<int>();
    private int[] _nextMembers = Array.Empty<int>();
    private CoarseLevel? _next;
    private CoarseLevel? _above; // the level a post-smoothing prolongs into
    private bool _smoothNext;
    private int _operation;
    private int _passCount;
    private int[] _nextTarget = Array.Empty<int>();
    private double[]? _dense;
    private bool _denseValid;

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

    public int Count { get; }

    /// <summary>
    /// The blocks: the diagonal ones (block i for row i), then each pair's off-diagonal block A_ij with i &lt; j once
    /// (block Count + slot of entry k; the entry (j, i) reads it transposed).
    /// </summary>
    public double[] Values { get; }

    public double[] Inverse { get; }

    public double[] B { get; }

    public double[] X { get; private set; }

    /// <summary>The buffer a post-smoothing writes into; <see cref="SwapSmoothed"/> makes it <see cref="X"/>.</summary>
    public double[] Smoothed => _smoothed;

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

    /// <summary>
    /// Inverts the diagonal blocks, in one pass over the rows (on the runner for large levels); a zero block (an
    /// aggregate of pinned particles only) becomes the identity.
    /// </summary>
    public void Invert(IParallelRunner? runner) => RunPass(InvertPass, Count, runner);

    /// <summary>Rows [begin, end) of <see cref="Invert"/>, then their blocks by columns for the lanes path.</summary>
    private void InvertRows(int begin, int end)
    {
        var d = Values;
        for (var i = begin; i < end; i++)
        {
            var o = 9 * i;
            if (d[o] == 0.0 && d[o + 4] == 0.0 && d[o + 8] == 0.0)
            {
                d[o] = d[o + 4] = d[o + 8] = 1.0;
            }

            if (!Blocks3.Invert(d, o, Inverse, o))
            {
                Array.Clear(Inverse, o, 9);
                Inverse[o] = 1.0 / Math.Max(d[o], double.Epsilon);
                Inverse[o + 4] = 1.0 / Math.Max(d[o + 4], double.Epsilon);
                Inverse[o + 8] = 1.0 / Math.Max(d[o + 8], double.Epsilon);
            }
        }

        if (Lanes)
        {
            fixed (double* values = Values, inverse = Inverse, lanes = _laneBlocks, inverseLanes = _laneInverse)
            {
                for (var i = begin; i < end; i++)
                {
                    LaneRow(i, values, inverse, lanes, inverseLanes);
                }
            }
        }
    }

    /// <summary>
    /// Row i's blocks and inverted diagonal block by columns for the lanes path: the diagonal block and each entry's
    /// block A_ij, a block right of the diagonal transposed from its row-major storage, one left of it copied as it
    /// is (its storage is A_ji = A_ij^T row by row, which is A_ij column by column).
    /// </summary>
    private void LaneRow(int i, double* values, double* inverse, double* lanes, double* inverseLanes)
    {
        var k = _rowStart[i];
        Transpose(values + (9L * i), lanes + (9L * (i + k)));
        Transpose(inverse + (9L * i), inverseLanes + (9L * i));
        for (; k < _rowStart[i + 1]; k++)
        {
            double* stored = values + (9L * (Count + _slot[k])), to = lanes + (9L * (i + 1 + k));
            if (k < _split[i])
            {
                for (var q = 0; q < 9; q++)
                {
                    to[q] = stored[q];
                }
            }
            else
            {
                Transpose(stored, to);
            }
        }
    }

    /// <summary>A row-major 3 x 3 block written by columns: to[3 c + r] = from[3 r + c].</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Transpose(double* from, double* to)
    {
        (to[0], to[1], to[2]) = (from[0], from[3], from[6]);
        (to[3], to[4], to[5]) = (from[1], from[4], from[7]);
        (to[6], to[7], to[8]) = (from[2], from[5], from[8]);
    }

    /// <summary>
    /// The next level's operator: every block of this one added where its row and column aggregates meet, in one pass
    /// over the next level's aggregates (on the runner for large levels). Row i's blocks all land in the row of its
    /// aggregate (its diagonal block, or a block right of it: a block whose aggregates are in decreasing order is
    /// left to its mirror, which the next level stores), so each aggregate assembles its own row from its members'
    /// rows, in increasing member order: every block gets its terms in increasing row order, as a loop over all the
    /// rows gives them, whatever the chunks.
    /// </summary>
    public void GalerkinInto(CoarseLevel next, IParallelRunner? runner)
    {
        _next = next;
        RunPass(GalerkinPass, next.Count, runner);
    }

    /// <summary>Aggregates [begin, end) of the next level's operator (see <see cref="GalerkinInto"/>): their rows cleared, then summed.</summary>
    private void GalerkinRows(int begin, int end, double* values, double* nextValues, int* rowStart, int* split, int* slot, int* start, int* members)
    {
        var next = _next!;
        var (first, last) = next.BlockRange(begin, end);
        new Span<double>(nextValues + (9L * first), 9 * (last - first)).Clear();
        var (offFirst, offLast) = next.OffDiagonalRange(begin, end);
        new Span<double>(nextValues + (9L * offFirst), 9 * (offLast - offFirst)).Clear();
        fixed (int* target = _nextTarget)
        {
            for (var a = begin; a < end; a++)
            {
                for (var m = start[a]; m < start[a + 1]; m++)
                {
                    // Row i's blocks A_ij in column order, those left of the diagonal read transposed.
                    var i = members[m];
                    Blocks3.Add(nextValues + (9L * a), values + (9L * i));
                    for (var k = rowStart[i]; k < split[i]; k++)
                    {
                        if (target[k] >= 0)
                        {
                            Blocks3.AddTransposed(nextValues + (9L * target[k]), values + (9L * (Count + slot[k])));
                        }
                    }

                    for (var k = split[i]; k < rowStart[i + 1]; k++)
                    {
                        if (target[k] >= 0)
                        {
                            Blocks3.Add(nextValues + (9L * target[k]), values + (9L * (Count + slot[k])));
                        }
                    }
                }
            }
        }
    }

    /// <summary>
    /// The next level's B = P^T (B - A X), with this level's X = D^-1 B already done, and when
    /// <paramref name="smoothNext"/> the next level's own pre-smoothing from zero, X_next = D_next^-1 B_next: one
    /// pass over the next level's aggregates, each summing its members' residual rows in increasing member order.
    /// </summary>
    public void RestrictResidual(CoarseLevel next, bool smoothNext, IParallelRunner? runner)
    {
        _next = next;
        _smoothNext = smoothNext;
        RunPass(ResidualRestrictPass, next.Count, runner);
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

    /// <summary>
    /// The post-smoothing sweep X + D^-1 (B - A X) after the prolongation, in one pass, with the prolongation into
    /// the level above: each row's new X added to its members there (X_above += P X, the additions of
    /// <see cref="Prolong"/>).
    /// </summary>
    public void PostSmooth(CoarseLevel next, CoarseLevel above, IParallelRunner? runner)
    {
        _next = next;
        _above = above;
        RunPass(PostSmoothPass, Count, runner);
        _above = null;
        SwapSmoothed();
    }

    /// <summary>Makes the buffer the post-smoothing wrote into this level's X.</summary>
    public void SwapSmoothed() => (X, _smoothed) = (_smoothed, X);

    /// <summary>
    /// Rows [begin, end) of the post-smoothing sweep (see <see cref="PostSmooth"/>) into <paramref name="outputs"/>
    /// (3 values per row), the level's arrays pinned once for the rows instead of once a row (94 instructions a row).
    /// </summary>
    public void PostSmoothRows(int begin, int end, double* outputs)
    {
        fixed (double* b = B, x = X, inverse = Inverse, values = Values, lanes = _laneBlocks, inverseLanes = _laneInverse)
        fixed (int* rowStart = _rowStart, column = _column, split = _split, slot = _slot)
        {
            for (var i = begin; i < end; i++)
            {
                PostSmoothRowCore(i, values, rowStart, column, split, slot, b, x, inverse, lanes, inverseLanes, outputs + (3L * i));
            }
        }
    }

    /// <summary>
    /// output = X_i + D_i^-1 (B_i - sum_j A_ij X_j) (X read only: the rows still to come need the old one), from
    /// the lanes copies (<paramref name="lanes"/>, <paramref name="inverseLanes"/>) where <see cref="Lanes"/>.
    /// </summary>
    private void PostSmoothRowCore(
        int i, double* values, int* rowStart, int* column, int* split, int* slot, double* b, double* x, double* inverse,
        double* lanes, double* inverseLanes, double* output)
    {
        if (Lanes)
        {
            // x_i + W r as W's columns scaled by r's components: per lane ((W_l0 r_0 + W_l1 r_1) + W_l2 r_2), as below.
            var rl = ResidualLanes(i, lanes, rowStart, column, b, x);
            var wi = inverseLanes + (9L * i);
            var t = (Load(wi) * new Vector<double>(rl[0])) + (Load(wi + 3) * new Vector<double>(rl[1]));
            var o = Load(x + (3L * i)) + (t + (Load(wi + 6) * new Vector<double>(rl[2])));
            output[0] = o[0];
            output[1] = o[1];
            output[2] = o[2];
            return;
        }

        var r = ResidualRow(i, values, rowStart, column, split, slot, b, x);
        double* w = inverse + (9L * i), xi = x + (3L * i);
        output[0] = xi[0] + ((w[0] * r.X) + (w[1] * r.Y) + (w[2] * r.Z));
        output[1] = xi[1] + ((w[3] * r.X) + (w[4] * r.Y) + (w[5] * r.Z));
        output[2] = xi[2] + ((w[6] * r.X) + (w[7] * r.Y) + (w[8] * r.Z));
    }

    /// <summary>Row i of the residual, B_i - A_ii X_i - sum_j A_ij X_j, in that order.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private Vector3d ResidualRow(int i, double* values, int* rowStart, int* column, int* split, int* slot, double* b, double* x)
    {
        double* d = values + (9L * i), xi = x + (3L * i);
        double x0 = xi[0], x1 = xi[1], x2 = xi[2];
        var bi = b + (3L * i);
        var r0 = bi[0] - ((d[0] * x0) + (d[1] * x1) + (d[2] * x2));
        var r1 = bi[1] - ((d[3] * x0) + (d[4] * x1) + (d[5] * x2));
        var r2 = bi[2] - ((d[6] * x0) + (d[7] * x1) + (d[8] * x2));
        int k = rowStart[i], middle = split[i], end = rowStart[i + 1];
        for (; k < middle; k++)
        {
            // Left of the diagonal: A_ij = A_ji^T, stored in row j.
            double* m = values + (9L * (Count + slot[k])), xj = x + (3L * column[k]);
            double y0 = xj[0], y1 = xj[1], y2 = xj[2];
            r0 -= (m[0] * y0) + (m[3] * y1) + (m[6] * y2);
            r1 -= (m[1] * y0) + (m[4] * y1) + (m[7] * y2);
            r2 -= (m[2] * y0) + (m[5] * y1) + (m[8] * y2);
        }

        for (; k < end; k++)
        {
            double* m = values + (9L * (Count + slot[k])), xj = x + (3L * column[k]);
            double y0 = xj[0], y1 = xj[1], y2 = xj[2];
            r0 -= (m[0] * y0) + (m[1] * y1) + (m[2] * y2);
            r1 -= (m[3] * y0) + (m[4] * y1) + (m[5] * y2);
            r2 -= (m[6] * y0) + (m[7] * y1) + (m[8] * y2);
        }

        return new Vector3d(r0, r1, r2);
    }

    /// <summary>
    /// <see cref="ResidualRow"/> with the row's three components as lanes (the fourth unused): each block times x_j
    /// as its columns scaled by x_j's components, ((A_l0 y_0 + A_l1 y_1) + A_l2 y_2) per lane, subtracted in the
    /// same order: the same bits.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector<double> ResidualLanes(int i, double* blocks, int* rowStart, int* column, double* b, double* x)
    {
        int k = rowStart[i], end = rowStart[i + 1];
        double* d = blocks + (9L * (i + k)), xi = x + (3L * i);
        var r = Load(b + (3L * i)) - ColumnsTimes(d, xi);
        for (; k < end; k++)
        {
            r -= ColumnsTimes(blocks + (9L * (i + 1 + k)), x + (3L * column[k]));
        }

        return r;
    }

    /// <summary>A block stored by columns times the 3-vector y, as lanes: (c_0 y_0 + c_1 y_1) + c_2 y_2.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector<double> ColumnsTimes(double* columns, double* y) =>
        ((Load(columns) * new Vector<double>(y[0])) + (Load(columns + 3) * new Vector<double>(y[1])))
        + (Load(columns + 6) * new Vector<double>(y[2]));

    /// <summary>Four values from <paramref name="at"/> (each array the lanes path reads has one value past its last row).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector<double> Load(double* at) => *(Vector<double>*)at;

    public void Execute(int chunk, int chunkCount)
    {
        var (begin, end) = Chunk.Range(chunk, chunkCount, _passCount);
        if (_operation == InvertPass)
        {
            InvertRows(begin, end);
            return;
        }

        fixed (double* b = B, x = X, smoothed = _smoothed, inverse = Inverse, values = Values, lanes = _laneBlocks, inverseLanes = _laneInverse)
        fixed (int* rowStart = _rowStart, column = _column, split = _split, slot = _slot)
        fixed (double* nextB = _next!.B, nextX = _next.X, nextInverse = _next.Inverse)
        fixed (int* aggregate = _nextAggregate, start = _nextMemberStart, members = _nextMembers)
        {
            if (_operation == GalerkinPass)
            {
                fixed (double* nextValues = _next.Values)
                {
                    GalerkinRows(begin, end, values, nextValues, rowStart, split, slot, start, members);
                }

                return;
            }

            if (_operation == PostSmoothPass)
            {
                var above = _above!;
                fixed (double* aboveX = above.X)
                fixed (int* aboveStart = above._nextMemberStart, aboveMembers = above._nextMembers)
                {
                    for (var i = begin; i < end; i++)
                    {
                        var c = smoothed + (3L * i);
                        PostSmoothRowCore(i, values, rowStart, column, split, slot, b, x, inverse, lanes, inverseLanes, c);
                        for (var m = aboveStart[i]; m < aboveStart[i + 1]; m++)
                        {
                            var xm = aboveX + (3L * aboveMembers[m]);
                            xm[0] += c[0];
                            xm[1] += c[1];
                            xm[2] += c[2];
                        }
                    }
                }

                return;
            }

            for (var a = begin; a < end; a++)
            {
                double b0 = 0.0, b1 = 0.0, b2 = 0.0;
                if (Lanes)
                {
                    var sum = Vector<double>.Zero; // the members' residual rows added lane by lane, in member order
                    for (var k = start[a]; k < start[a + 1]; k++)
                    {
                        sum += ResidualLanes(members[k], lanes, rowStart, column, b, x);
                    }

                    (b0, b1, b2) = (sum[0], sum[1], sum[2]);
                }
                else
                {
                    for (var k = start[a]; k < start[a + 1]; k++)
                    {
                        var r = ResidualRow(members[k], values, rowStart, column, split, slot, b, x); // member k's residual row
                        b0 += r.X;
                        b1 += r.Y;
                        b2 += r.Z;
                    }
                }

                var nb = nextB + (3L * a);
                nb[0] = b0;
                nb[1] = b1;
                nb[2] = b2;
                if (_smoothNext)
                {
                    Blocks3.Multiply(nextInverse + (9L * a), nb, nextX + (3L * a));
                }
            }
        }
    }

    /// <summary>Runs a pass over <paramref name="count"/> items in <see cref="AggregationMultigrid.Chunks"/> chunks: on the runner for large levels.</summary>
    private void RunPass(int operation, int count, IParallelRunner? runner)
    {
        _operation = operation;
        _passCount = count;
        Chunk.RunAll(Count >= ParallelRows ? runner : null, this, AggregationMultigrid.Chunks); // small levels stay on the calling thread
    }

    /// <summary>The map of this level's rows into the next level's aggregates (empty on the coarsest).</summary>
    public int[] NextAggregate => _nextAggregate;

    /// <summary>The operator as a dense row-major matrix, 3 Count values a side (for tests: it allocates).</summary>
    public double[] Dense()
    {
        var n = 3 * Count;
        var a = new double[n * n];
        FillDense(a, n);
        return a;
    }

    /// <summary>Writes the operator into <paramref name="a"/>, dense and row-major with <paramref name="n"/> = 3 Count.</summary>
    private void FillDense(double[] a, int n)
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

    /// <summary>Factorises the dense operator of a small level (Cholesky); block Jacobi if it is large or not positive definite.</summary>
    public void FactorDense()
    {
        _denseValid = false;
        if (Count > AggregationMultigrid.CoarsestNodes)
        {
            return;
        }

        var n = 3 * Count;
        _dense ??= new double[n * n];
        var a = _dense;
        Array.Clear(a, 0, a.Length);
        FillDense(a, n);
        _denseValid = DenseLinearSolver.FactorCholesky(a, n);
    }

    /// <summary>X = A^-1 B by the Cholesky factors, or X = D^-1 B when there are none.</summary>
    public void SolveCoarsest()
    {
        if (!_denseValid)
        {
            fixed (double* b = B, x = X, inverse = Inverse)
            {
                Blocks3.MultiplyAll(inverse, b, x, Count);
            }

            return;
        }

        DenseLinearSolver.SolveCholesky(_dense!, 3 * Count, B, X);
    }
}
