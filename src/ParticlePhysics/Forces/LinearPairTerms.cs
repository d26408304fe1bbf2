using System;
using System.Numerics;
using System.Runtime.InteropServices;
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

    /// <summary>Writes the pairs of the elements: the couplings of their Jacobian.</summary>
    public static void WriteCouplings(ForceElements pairs, Span<int> first, Span<int> second)
    {
        pairs.First.AsSpan(0, pairs.Count).CopyTo(first);
        pairs.Second.AsSpan(0, pairs.Count).CopyTo(second);
    }

    /// <summary>Adds each element's off-diagonal block J_ij = J_ji = (c scale) I, the opposite of its diagonal share, at its targets.</summary>
    public static void AddCouplingBlocks(
        ForceElements pairs, Span<double> destination, ReadOnlySpan<int> forwardBlock, ReadOnlySpan<int> backwardBlock, double scale)
    {
        CheckTargets(pairs.Count, destination.Length, forwardBlock, backwardBlock);
        var forward = forwardBlock.ForReading();
        var backward = backwardBlock.ForReading();
        for (var s = 0; s < pairs.Count; s++)
        {
            var k = pairs.Parameters[s] * scale;
            if (forward[s] >= 0)
            {
                var f = 9 * forward[s];
                destination[f] += k;
                destination[f + 4] += k;
                destination[f + 8] += k;
            }

            if (backward[s] >= 0)
            {
                var b = 9 * backward[s];
                destination[b] += k;
                destination[b + 4] += k;
                destination[b + 8] += k;
            }
        }
    }

    /// <summary>Checks that there is a forward and a backward index per element and that every index names a block of the destination.</summary>
    public static void CheckTargets(int count, int destinationLength, ReadOnlySpan<int> forwardBlock, ReadOnlySpan<int> backwardBlock)
    {
        if (forwardBlock.Length != count || backwardBlock.Length != count)
        {
            throw new ArgumentException(
                $"There must be one forward and one backward block index per coupling, {count}; got {forwardBlock.Length} and {backwardBlock.Length}.");
        }

        var blocks = destinationLength / 9;
        var forward = forwardBlock.ForReading();
        var backward = backwardBlock.ForReading();
        var s = 0;
        if (Vector.IsHardwareAccelerated)
        {
            // Several couplings at a time where the runtime has SIMD (the check runs at every step of the multigrid);
            // a chunk with a target out of range is left to the loop below, which names it.
            var limit = new Vector<int>(blocks);
            var forwards = MemoryMarshal.Cast<int, Vector<int>>(forward);
            var backwards = MemoryMarshal.Cast<int, Vector<int>>(backward);
            for (var v = 0; v < forwards.Length && Vector.LessThanAll(Vector.Max(forwards[v], backwards[v]), limit); v++)
            {
                s += Vector<int>.Count;
            }
        }

        for (; s < count; s++)
        {
            if (forward[s] >= blocks || backward[s] >= blocks)
            {
                throw new ArgumentOutOfRangeException(
                    nameof(forwardBlock), $"Coupling {s} targets blocks {forward[s]} and {backward[s]}; the destination holds {blocks}.");
            }
        }
    }
}
