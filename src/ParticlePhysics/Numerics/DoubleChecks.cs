using System;
using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;

namespace ParticlePhysics.Numerics;

/// <summary>Finiteness tests over numbers and buffers (netstandard2.1 has no double.IsFinite on every runtime Unity ships).</summary>
internal static class DoubleChecks
{
    /// <summary>True when <paramref name="value"/> is neither NaN nor infinite.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static bool IsFinite(double value) => (value - value) == 0.0;

    /// <summary>The index of the first entry that is NaN or infinite, or -1 when all are finite.</summary>
    public static int FirstNonFinite(ReadOnlySpan<double> values)
    {
        var v = values.ForReading();
        for (var i = 0; i < values.Length; i++)
        {
            if ((v[i] - v[i]) != 0.0)
            {
                return i;
            }
        }

        return -1;
    }

    /// <summary>
    /// The index of the first entry that is NaN, infinite or larger than <paramref name="limit"/> in magnitude,
    /// or -1 when all are within it. One comparison per value: NaN fails every comparison.
    /// </summary>
    public static int FirstBeyond(ReadOnlySpan<double> values, double limit)
    {
        var v = values.ForReading();
        var start = 0;
        if (Vector.IsHardwareAccelerated)
        {
            // Whole vectors first: |v| <= limit is false for NaN, so one comparison per lane catches everything.
            var vectors = MemoryMarshal.Cast<double, Vector<double>>(v);
            var bound = new Vector<double>(limit);
            for (var j = 0; j < vectors.Length; j++)
            {
                if (!Vector.LessThanOrEqualAll(Vector.Abs(vectors[j]), bound))
                {
                    start = j * Vector<double>.Count;
                    break;
                }

                start = (j + 1) * Vector<double>.Count;
            }
        }

        for (var i = start; i < values.Length; i++)
        {
            if (!(Math.Abs(v[i]) <= limit))
            {
                return i;
            }
        }

        return -1;
    }
}
