using System;

namespace ParticlePhysics.Tests.Support;

/// <summary>
/// SplitMix64 (Steele, Lea and Flood, 2014): a tiny generator whose sequence depends on its seed alone, on every
/// runtime and version (System.Random's does not promise that), so that a fuzz run is reproduced from its seed.
/// </summary>
internal sealed class SeededRandom
{
    // Numbers worth trying in a bad-input fuzzer: the edges of the doubles and of what the library accepts.
    private static readonly double[] _edges =
    {
        0.0, -0.0, 1.0, -1.0, 0.5, 1e-3, 1e-12, 1e-320, 5e-324, 4.9e-309, 5.56268464626801e-309, 1e12, 1.1e12, 1e100,
        1e300, 1e308, double.MaxValue, -double.MaxValue, double.Epsilon, double.NaN, double.PositiveInfinity,
        double.NegativeInfinity, 2.220446049250313e-16, 2.2e-14,
    };

    private ulong _state;

    public SeededRandom(ulong seed)
    {
        _state = seed;
    }

    public ulong NextUInt64()
    {
        var z = _state += 0x9E3779B97F4A7C15UL;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9UL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBUL;
        return z ^ (z >> 31);
    }

    /// <summary>A whole number from 0 to <paramref name="count"/> - 1.</summary>
    public int Next(int count) => (int)(NextUInt64() % (ulong)count);

    /// <summary>A whole number from <paramref name="low"/> to <paramref name="high"/> - 1.</summary>
    public int Next(int low, int high) => low + Next(high - low);

    /// <summary>A double uniform in [0, 1).</summary>
    public double NextDouble() => (NextUInt64() >> 11) * (1.0 / (1UL << 53));

    /// <summary>True with probability <paramref name="p"/>.</summary>
    public bool Chance(double p) => NextDouble() < p;

    /// <summary>A double uniform in [<paramref name="low"/>, <paramref name="high"/>).</summary>
    public double Between(double low, double high) => low + ((high - low) * NextDouble());

    /// <summary>Usually a value in [<paramref name="low"/>, <paramref name="high"/>), sometimes (<paramref name="bad"/>) an edge value.</summary>
    public double Value(double low, double high, double bad = 0.15) =>
        Chance(bad) ? _edges[Next(_edges.Length)] : Between(low, high);

    /// <summary>One of <paramref name="items"/>.</summary>
    public T Pick<T>(params T[] items) => items[Next(items.Length)];
}
