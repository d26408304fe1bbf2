using System;
using System.Runtime.CompilerServices;

namespace ParticlePhysics.Numerics;

/// <summary>Row-major 3 x 3 block arithmetic: the diagonal blocks of the implicit solver and its preconditioners.</summary>
internal static unsafe class Blocks3
{
    /// <summary>Writes the inverse of the block at a[o] into inverse[p] by cofactors; false if it is singular or not finite.</summary>
    public static bool Invert(double[] a, int o, double[] inverse, int p)
    {
        if (o < 0 || p < 0 || a.Length - 9 < o || inverse.Length - 9 < p)
        {
            throw new ArgumentOutOfRangeException(nameof(o), "A 3 x 3 block needs 9 values from its offset.");
        }

        fixed (double* source = a, target = inverse)
        {
            return Invert(source + o, target + p);
        }
    }

    /// <summary>
    /// Writes the inverse of the block at <paramref name="a"/> into <paramref name="inverse"/> by cofactors (the two may
    /// be the same block: every value is read before any is written); false if it is singular or not finite.
    /// </summary>
    public static bool Invert(double* a, double* inverse)
    {
        double m00 = a[0], m01 = a[1], m02 = a[2];
        double m10 = a[3], m11 = a[4], m12 = a[5];
        double m20 = a[6], m21 = a[7], m22 = a[8];
        double c00 = (m11 * m22) - (m12 * m21), c01 = (m02 * m21) - (m01 * m22), c02 = (m01 * m12) - (m02 * m11);
        double c10 = (m12 * m20) - (m10 * m22), c11 = (m00 * m22) - (m02 * m20), c12 = (m02 * m10) - (m00 * m12);
        double c20 = (m10 * m21) - (m11 * m20), c21 = (m01 * m20) - (m00 * m21), c22 = (m00 * m11) - (m01 * m10);
        var determinant = (m00 * c00) + (m01 * c10) + (m02 * c20);
        if (!(Math.Abs(determinant) > 0.0) || double.IsInfinity(determinant) || double.IsNaN(determinant))
        {
            return false;
        }

        var s = 1.0 / determinant;
        inverse[0] = c00 * s;
        inverse[1] = c01 * s;
        inverse[2] = c02 * s;
        inverse[3] = c10 * s;
        inverse[4] = c11 * s;
        inverse[5] = c12 * s;
        inverse[6] = c20 * s;
        inverse[7] = c21 * s;
        inverse[8] = c22 * s;
        return true;
    }

    /// <summary>
    /// Writes the inverse of the symmetric block with upper triangle (a00, a01, a02, a11, a12, a22) into
    /// <paramref name="packed"/> as its upper triangle, by cofactors; false (nothing written) if it is singular or not
    /// finite. The operations of <see cref="Invert(double*, double*)"/> on the full symmetric block, whose mirrored
    /// cofactors are the same two products (c10 = c01, c20 = c02, c21 = c12 to the last bit): the same bits, with 6
    /// cofactors instead of 9.
    /// </summary>
    public static bool InvertSymmetric(double a00, double a01, double a02, double a11, double a12, double a22, double* packed)
    {
        double c00 = (a11 * a22) - (a12 * a12), c01 = (a02 * a12) - (a01 * a22), c02 = (a01 * a12) - (a02 * a11);
        double c11 = (a00 * a22) - (a02 * a02), c12 = (a02 * a01) - (a00 * a12), c22 = (a00 * a11) - (a01 * a01);
        var determinant = (a00 * c00) + (a01 * c01) + (a02 * c02);
        if (!(Math.Abs(determinant) > 0.0) || double.IsInfinity(determinant) || double.IsNaN(determinant))
        {
            return false;
        }

        var s = 1.0 / determinant;
        packed[0] = c00 * s;
        packed[1] = c01 * s;
        packed[2] = c02 * s;
        packed[3] = c11 * s;
        packed[4] = c12 * s;
        packed[5] = c22 * s;
        return true;
    }

    /// <summary>target += source (9 values).</summary>
    public static void Add(double* target, double* source)
    {
        target[0] += source[0];
        target[1] += source[1];
        target[2] += source[2];
        target[3] += source[3];
        target[4] += source[4];
        target[5] += source[5];
        target[6] += source[6];
        target[7] += source[7];
        target[8] += source[8];
    }

    /// <summary>target += source^T (9 values).</summary>
    public static void AddTransposed(double* target, double* source)
    {
        target[0] += source[0];
        target[1] += source[3];
        target[2] += source[6];
        target[3] += source[1];
        target[4] += source[4];
        target[5] += source[7];
        target[6] += source[2];
        target[7] += source[5];
        target[8] += source[8];
    }

    /// <summary>y = M x for one block (y may not be x).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void Multiply(double* m, double* x, double* y)
    {
        double x0 = x[0], x1 = x[1], x2 = x[2];
        y[0] = (m[0] * x0) + (m[1] * x1) + (m[2] * x2);
        y[1] = (m[3] * x0) + (m[4] * x1) + (m[5] * x2);
        y[2] = (m[6] * x0) + (m[7] * x1) + (m[8] * x2);
    }

    /// <summary>
    /// y = M x for a symmetric block stored as its upper triangle xx, xy, xz, yy, yz, zz, with the operations
    /// of <see cref="Multiply"/> on the full block (y may not be x).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void MultiplySymmetric(double* m, double* x, double* y)
    {
        double x0 = x[0], x1 = x[1], x2 = x[2];
        y[0] = (m[0] * x0) + (m[1] * x1) + (m[2] * x2);
        y[1] = (m[1] * x0) + (m[3] * x1) + (m[4] * x2);
        y[2] = (m[2] * x0) + (m[4] * x1) + (m[5] * x2);
    }

    /// <summary>y_i = M_i x_i for <paramref name="count"/> blocks.</summary>
    public static void MultiplyAll(double* blocks, double* x, double* y, int count)
    {
        for (var i = 0; i < count; i++)
        {
            Multiply(blocks + (9L * i), x + (3L * i), y + (3L * i));
        }
    }
}
