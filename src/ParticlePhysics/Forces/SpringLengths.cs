using System;
using System.Numerics;

namespace ParticlePhysics.Forces;

/// <summary>
/// The lengths l = |x_a - x_b| and their inverses 1 / l for a block of springs, in a loop of their own: the square
/// root and the division that every spring's linearisation waits on (some 35 cycles together), taken out of the long
/// loop body that uses them (forces, linearisation and (df/dx) v, some 150 instructions a spring), so that the
/// processor overlaps many springs' worth of them instead of the less than two that fit its window in that body, and,
/// where the runtime accelerates System.Numerics.Vector (CoreCLR), takes them several springs at a time. The
/// linearisation runs over blocks of <see cref="Block"/> springs: this first, then its own arithmetic with l and
/// 1 / l read back (the same operations, so the same bits). The force loop alone, a third as long, overlaps enough
/// by itself and is not split.
/// </summary>
internal static unsafe class SpringLengths
{
    /// <summary>
    /// The springs per block: enough for the processor to overlap their square roots and divisions; the size matters
    /// little beyond that.
    /// </summary>
    public const int Block = 64;

    /// <summary>
    /// Writes l of springs [<paramref name="begin"/>, <paramref name="end"/>) into
    /// <paramref name="roots"/>[s - begin] and 1 / l into <paramref name="roots"/>[<see cref="Block"/> + s - begin]
    /// (at l = 0, 1 / l is +infinity: a caller tests l = 0, which holds exactly when l^2 = 0, and does not use it). At
    /// most <see cref="Block"/> springs; <paramref name="roots"/> holds 2 <see cref="Block"/> values.
    /// </summary>
    /// <remarks>
    /// The squared lengths first, spring by spring (each gathers its two ends), then the square roots and divisions
    /// over the block: with SIMD where the runtime accelerates it, a plain loop otherwise. A square root and a division
    /// are correctly rounded in IEEE 754 whether one value or several are taken at once, so both paths give the same
    /// bits.
    /// </remarks>
    public static void Compute(double* x, int* first, int* second, int begin, int end, double* roots)
    {
        var count = end - begin;
        for (var s = begin; s < end; s++)
        {
            long a = 3 * first[s], b = 3 * second[s];
            double dx = x[a] - x[b], dy = x[a + 1] - x[b + 1], dz = x[a + 2] - x[b + 2];
            roots[s - begin] = (dx * dx) + (dy * dy) + (dz * dz);
        }

        var k = 0;
        if (Vector.IsHardwareAccelerated)
        {
            var lengths = new Span<Vector<double>>(roots, count / Vector<double>.Count);
            var inverses = new Span<Vector<double>>(roots + Block, count / Vector<double>.Count);
            for (var j = 0; j < lengths.Length; j++)
            {
                var length = Vector.SquareRoot(lengths[j]);
                lengths[j] = length;
                inverses[j] = Vector<double>.One / length;
            }

            k = lengths.Length * Vector<double>.Count;
        }

        for (; k < count; k++)
        {
            var length = Math.Sqrt(roots[k]);
            roots[k] = length;
            roots[Block + k] = 1.0 / length;
        }
    }
}
