using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Forces;

/// <summary>
/// The pair terms linear in one buffer, shared by <see cref="ZeroLengthSprings"/> (on positions) and
/// <see cref="Dampers"/> (on velocities): with c the element's coefficient, y = -s c (w_i - w_j) is added at i and
/// subtracted at j. With s = 1 that is the force; with s the implicit step's scale, the Jacobian product.
/// </summary>
internal static class LinearPairTerms
{
    public static void AddScaledDifferences(ForceElements pairs, ReadOnlySpan<double> w, Span<double> result, double scale)
    {
        var wr = w.ForReading();
        var first = pairs.First;
        var second = pairs.Second;
        var c = pairs.Parameters;
        for (var s = 0; s < pairs.Count; s++)
        {
            int a = 3 * first[s], b = 3 * second[s];
            var k = -c[s] * scale;
            var yx = k * (wr[a] - wr[b]);
            var yy = k * (wr[a + 1] - wr[b + 1]);
            var yz = k * (wr[a + 2] - wr[b + 2]);
            result[a] += yx;
            result[a + 1] += yy;
            result[a + 2] += yz;
            result[b] -= yx;
            result[b + 1] -= yy;
            result[b + 2] -= yz;
        }
    }

    /// <summary>Adds -s c I to the diagonal blocks of both ends of every pair.</summary>
    public static void AddDiagonalBlocks(ForceElements pairs, Span<double> blocks, double scale)
    {
        for (var s = 0; s < pairs.Count; s++)
        {
            var k = -pairs.Parameters[s] * scale;
            JacobianBlocks.AddIsotropic(blocks, pairs.First[s], k);
            JacobianBlocks.AddIsotropic(blocks, pairs.Second[s], k);
        }
    }
}
