using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Tests.Aerodynamics;

/// <summary>The library's own sine, cosine and atan2 (+ - * / and sqrt only) against the platform's, and their symmetries to the bit.</summary>
public class DeterministicTrigTests
{
    [Theory]
    [InlineData(4.0, 2.3e-16)] // one unit in the last place of a value near 1
    [InlineData(1e4, 4e-16)]
    [InlineData(1.6e6, 1e-15)]
    public void Sine_and_cosine_agree_with_the_platforms_within_rounding(double range, double tolerance)
    {
        var random = new Random(17);
        var worst = 0.0;
        for (var k = 0; k < 200_000; k++)
        {
            var x = range * ((2 * random.NextDouble()) - 1);
            worst = Math.Max(worst, Math.Abs(DeterministicTrig.Sin(x) - Math.Sin(x)));
            worst = Math.Max(worst, Math.Abs(DeterministicTrig.Cos(x) - Math.Cos(x)));
        }

        Assert.True(worst <= tolerance, $"worst difference {worst:R} over |x| <= {range}");
    }

    [Fact]
    public void Exact_values_and_symmetries_hold_to_the_bit()
    {
        Assert.Equal(0.0, DeterministicTrig.Sin(0.0));
        Assert.Equal(1.0, DeterministicTrig.Cos(0.0));
        Assert.Equal(1.0, DeterministicTrig.Sin(Math.PI / 2));
        Assert.Equal(-1.0, DeterministicTrig.Cos(Math.PI));
        var random = new Random(3);
        for (var k = 0; k < 10_000; k++)
        {
            var x = 100 * random.NextDouble();
            Assert.Equal(-DeterministicTrig.Sin(x), DeterministicTrig.Sin(-x));
            Assert.Equal(DeterministicTrig.Cos(x), DeterministicTrig.Cos(-x));
        }
    }

    [Fact]
    public void Atan2_agrees_with_the_platforms_in_every_quadrant_within_rounding()
    {
        var random = new Random(29);
        var worst = 0.0;
        for (var k = 0; k < 200_000; k++)
        {
            var scale = Math.Pow(10, (random.NextDouble() * 12) - 6);
            var y = scale * ((2 * random.NextDouble()) - 1);
            var x = (k % 7 == 0 ? 1e-3 : 1.0) * scale * ((2 * random.NextDouble()) - 1);
            worst = Math.Max(worst, Math.Abs(DeterministicTrig.Atan2(y, x) - Math.Atan2(y, x)));
        }

        Assert.True(worst <= 1e-15, $"worst difference {worst:R}");
        foreach (var (y, x) in new[] { (0.0, 0.0), (-0.0, 0.0), (0.0, -0.0), (-0.0, -0.0), (1.0, 0.0), (-1.0, 0.0), (0.0, -1.0), (-0.0, -1.0), (1.0, 1.0), (-2.0, -2.0) })
        {
            Assert.Equal(Math.Atan2(y, x), DeterministicTrig.Atan2(y, x), 15);
            Assert.Equal(Math.Sign(Math.Atan2(y, x)), Math.Sign(DeterministicTrig.Atan2(y, x)));
            Assert.Equal(BitConverter.DoubleToInt64Bits(Math.Atan2(y, x)) < 0, BitConverter.DoubleToInt64Bits(DeterministicTrig.Atan2(y, x)) < 0);
        }

        Assert.True(double.IsNaN(DeterministicTrig.Atan2(double.NaN, 1.0)));
        Assert.True(double.IsNaN(DeterministicTrig.Atan2(1.0, double.PositiveInfinity)));
    }

    [Theory]
    [InlineData(double.NaN)]
    [InlineData(double.PositiveInfinity)]
    [InlineData(double.NegativeInfinity)]
    [InlineData(2e15)]
    public void What_cannot_be_reduced_is_not_a_number(double x)
    {
        Assert.True(double.IsNaN(DeterministicTrig.Sin(x)));
        Assert.True(double.IsNaN(DeterministicTrig.Cos(x)));
    }

    [Fact]
    public void A_thousand_values_hash_to_the_golden_bits()
    {
        // The same bits on every runtime: this hash is held on .NET here, and .ci/mono compares the gusty flag's.
        ulong hash = 1469598103934665603;
        for (var k = 0; k < 1000; k++)
        {
            var x = (k * 0.731) - 300.0;
            hash = (hash ^ (ulong)BitConverter.DoubleToInt64Bits(DeterministicTrig.Sin(x))) * 1099511628211;
            hash = (hash ^ (ulong)BitConverter.DoubleToInt64Bits(DeterministicTrig.Cos(x))) * 1099511628211;
        }

        Assert.Equal(8789884191167964505UL, hash);
    }
}
