using System;

namespace ParticlePhysics.Forces;

/// <summary>
/// The lengths l = |x_a - x_b| and their inverses 1 / l for a block of springs, in a loop of their own: the square
/// root and the division that every spring's linearisation waits on (some 35 cycles together), taken out of the long
/// loop body that uses them (forces, linearisation and (df/dx) v, some 150 instructions a spring), so that the
/// processor overlaps many springs' worth of them instead of the less than two that fit its window in that body. The
/// linearisation runs over blocks of <see cref="Block"/> springs: this first, then its own arithmetic with l and
/// 1 / l read back (the same operations, so the same bits). The force loop alone, a third as long, overlaps enough
/// by itself: split the same way it ran no faster (258 against 258 us on the 64 x 64 cloth).
/// </summary>
internal static unsafe class SpringLengths
{
    /// <summary>
    /// The springs per block. Measured on the 64 x 64 cloth's spring loop of the fused forces and linearisation
    /// (23 938 springs, one core, the fastest of 40 alternating rounds): 504 us in one loop; in blocks of 16, 32, 64
    /// and 128 springs 410, 409, 403 and 405 us.
    /// </summary>
    public const int Block = 64;

    /// <summary>
    /// Writes l and 1 / l of springs [<paramref name="begin"/>, <paramref name="end"/>) into
    /// <paramref name="roots"/>[2 (s - begin)] and [2 (s - begin) + 1] (at l = 0, 1 / l is +infinity: a caller tests
    /// l = 0, which holds exactly when l^2 = 0, and does not use it). At most <see cref="Block"/> springs.
    /// </summary>
    public static void Compute(double* x, int* first, int* second, int begin, int end, double* roots)
    {
        for (var s = begin; s < end; s++)
        {
            long a = 3 * first[s], b = 3 * second[s];
            double dx = x[a] - x[b], dy = x[a + 1] - x[b + 1], dz = x[a + 2] - x[b + 2];
            var length = Math.Sqrt((dx * dx) + (dy * dy) + (dz * dz));
            var r = roots + (2 * (s - begin));
            r[0] = length;
            r[1] = 1.0 / length;
        }
    }
}
