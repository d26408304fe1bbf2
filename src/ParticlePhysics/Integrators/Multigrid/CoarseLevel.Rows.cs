using System.Numerics;
using System.Runtime.CompilerServices;

namespace ParticlePhysics.Integrators.Multigrid;

/// <summary>
/// A coarse level's operator applied one row at a time, the kernels of its sweeps: the row of the residual B - A X,
/// and the row of the post-smoothing X + D^-1 (B - A X), each with a lanes twin of the same bits.
/// </summary>
internal sealed unsafe partial class CoarseLevel
{
    /// <summary>
    /// Rows [begin, end) of the post-smoothing sweep into <paramref name="outputs"/> (3 values per row), the level's
    /// arrays pinned once for the rows rather than once a row.
    /// </summary>
    public void PostSmoothRows(int begin, int end, double* outputs)
    {
        fixed (double* b = B, x = X, inverse = Inverse, values = Values, lanes = _laneBlocks, inverseLanes = _laneInverse)
        fixed (int* rowStart = _rowStart, column = _column, split = _split, slot = _slot)
        {
            for (var i = begin; i < end; i++)
            {
                PostSmoothRow(i, values, rowStart, column, split, slot, b, x, inverse, lanes, inverseLanes, outputs + (3L * i));
            }
        }
    }

    /// <summary>
    /// output = X_i + D_i^-1 (B_i - sum_j A_ij X_j) (X read only: the rows still to come need the old one), from
    /// the lanes copies (<paramref name="lanes"/>, <paramref name="inverseLanes"/>) where <see cref="Lanes"/>.
    /// </summary>
    public void PostSmoothRow(
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
    public Vector3d ResidualRow(int i, double* values, int* rowStart, int* column, int* split, int* slot, double* b, double* x)
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
    public static Vector<double> ResidualLanes(int i, double* blocks, int* rowStart, int* column, double* b, double* x)
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
}
