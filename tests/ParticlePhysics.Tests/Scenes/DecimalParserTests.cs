using System;
using System.Globalization;
using System.Numerics;
using System.Text;
using ParticlePhysics.Scenes.Text;

namespace ParticlePhysics.Tests.Scenes;

/// <summary>
/// The scenes' number parser against an independent oracle: .NET's own double.Parse, correctly rounded since .NET Core
/// 3.0 (IEEE 754-2008 conformance). The parser exists because Mono's is not; .ci/mono checks it gives the same bits there.
/// </summary>
public class DecimalParserTests
{
    private static double Oracle(string text) => double.Parse(text, NumberStyles.Float, CultureInfo.InvariantCulture);

    private static void AssertSameAsOracle(string text)
    {
        Assert.True(DecimalParser.TryParse(text.AsSpan(), out var value), text);
        Assert.Equal(BitConverter.DoubleToInt64Bits(Oracle(text)), BitConverter.DoubleToInt64Bits(value));
        Assert.True(DecimalParser.TryParse(Encoding.ASCII.GetBytes(text), out var fromBytes), text);
        Assert.Equal(BitConverter.DoubleToInt64Bits(value), BitConverter.DoubleToInt64Bits(fromBytes));
    }

    [Theory]
    [InlineData("0")]
    [InlineData("-0")]
    [InlineData("0.1")]
    [InlineData("9.81")]
    [InlineData("-1.5e3")]
    [InlineData(".5")]
    [InlineData("5.")]
    [InlineData("+7")]
    [InlineData("1E+2")]
    [InlineData("0.30000000000000004")]
    [InlineData("9007199254740993")] // 2^53 + 1: a tie, to even
    [InlineData("9007199254740995")]
    [InlineData("123456789012345678901234567890")]
    [InlineData("1e23")] // the classic: 1e23 is not 10^22 * 10 in doubles
    [InlineData("8.98846567431158e307")]
    [InlineData("1.7976931348623157e308")]
    [InlineData("1.7976931348623158e308")] // rounds down to double.MaxValue
    [InlineData("2.2250738585072011e-308")] // just below the least normal
    [InlineData("2.2250738585072014e-308")]
    [InlineData("4.9406564584124654e-324")]
    [InlineData("2.4703282292062328e-324")] // just above half the least subnormal: rounds up to it
    [InlineData("2.4703282292062327e-324")] // just below: rounds to 0
    [InlineData("1e-400")]
    [InlineData("-1e-400")]
    [InlineData("0.000000000000000000000000000000000000001")]
    [InlineData("1.00000000000000011102230246251565404236316680908203125")] // exactly halfway above 1
    [InlineData("1.00000000000000011102230246251565404236316680908203126")]
    [InlineData("-2.2929393e-273")] // Mono 6.8 gives one ulp off for these three
    [InlineData("-3.3425e-165")]
    [InlineData("-4.9e-151")]
    public void Known_hard_cases_parse_to_the_nearest_double(string text) => AssertSameAsOracle(text);

    [Theory]
    [InlineData("")]
    [InlineData("-")]
    [InlineData(".")]
    [InlineData("e5")]
    [InlineData("1e")]
    [InlineData("1e+")]
    [InlineData("1.2.3")]
    [InlineData("+-1")]
    [InlineData(" 1")]
    [InlineData("1 ")]
    [InlineData("0x10")]
    [InlineData("NaN")]
    [InlineData("Infinity")]
    [InlineData("1e309")]
    [InlineData("1.8e308")]
    [InlineData("1e99999999999999999999")]
    public void Malformed_or_out_of_range_text_is_refused(string text)
    {
        Assert.False(DecimalParser.TryParse(text.AsSpan(), out _));
        Assert.False(DecimalParser.TryParse(Encoding.ASCII.GetBytes(text), out _));
    }

    [Fact]
    public void Huge_negative_exponents_are_zero_and_huge_digit_strings_parse()
    {
        AssertSameAsOracle("1e-99999999999999999999");
        AssertSameAsOracle("0." + new string('0', 400) + "1");
        AssertSameAsOracle(new string('9', 300));
        AssertSameAsOracle("0." + new string('3', 500));
    }

    [Fact]
    public void Random_numbers_of_1_to_40_digits_at_every_exponent_parse_to_the_nearest_double()
    {
        var random = new Random(20261203);
        var builder = new StringBuilder();
        for (var k = 0; k < 50_000; k++)
        {
            builder.Clear();
            if (random.Next(2) == 0)
            {
                builder.Append('-');
            }

            var digits = random.Next(1, 41);
            var point = random.Next(0, digits + 1);
            for (var d = 0; d < digits; d++)
            {
                if (d == point && d > 0)
                {
                    builder.Append('.');
                }

                builder.Append((char)('0' + random.Next(10)));
            }

            builder.Append('e').Append(random.Next(-345, 330).ToString(CultureInfo.InvariantCulture));
            var text = builder.ToString();
            var oracle = Oracle(text);
            if (double.IsInfinity(oracle))
            {
                Assert.False(DecimalParser.TryParse(text.AsSpan(), out _), text);
                continue;
            }

            AssertSameAsOracle(text);
        }
    }

    [Fact]
    public void Exact_halfway_points_between_doubles_and_their_neighbours_round_as_the_oracle_does()
    {
        // The midpoint of d and the next double up, written out exactly in decimal, then with a digit more or less
        // in its last place: the cases a parser that rounds twice gets wrong.
        var random = new Random(7);
        for (var k = 0; k < 3_000; k++)
        {
            var bits = ((long)random.Next(1, 2046) << 52) | ((long)random.Next() << 21) | (long)random.Next(1 << 21);
            if (k % 10 == 0)
            {
                bits = (long)random.Next() << random.Next(0, 22); // subnormals
            }

            var midpoint = ExactMidpointAbove(BitConverter.Int64BitsToDouble(bits));
            AssertSameAsOracle(midpoint);
            AssertSameAsOracle(midpoint + (midpoint.Contains('.', StringComparison.Ordinal) ? "1" : ".1"));
            var last = midpoint[midpoint.Length - 1];
            if (last is > '0' and <= '9' && midpoint.Contains('.', StringComparison.Ordinal))
            {
                AssertSameAsOracle(midpoint.Substring(0, midpoint.Length - 1) + (char)(last - 1));
            }
        }
    }

    /// <summary>(d + next double) / 2 in exact decimal: (2 m + 1) 2^(e - 1) for d = m 2^e.</summary>
    private static string ExactMidpointAbove(double d)
    {
        var bits = BitConverter.DoubleToInt64Bits(d);
        var biased = (int)((bits >> 52) & 0x7FF);
        var fraction = bits & ((1L << 52) - 1);
        var m = biased == 0 ? fraction : fraction | (1L << 52);
        var e = (biased == 0 ? 1 : biased) - 1075;
        var numerator = (2 * new BigInteger(m)) + 1;
        var twoPower = e - 1;
        if (twoPower >= 0)
        {
            return (numerator << twoPower).ToString(CultureInfo.InvariantCulture);
        }

        // numerator / 2^k = numerator 5^k / 10^k.
        var k = -twoPower;
        var digits = (numerator * BigInteger.Pow(5, k)).ToString(CultureInfo.InvariantCulture);
        if (digits.Length <= k)
        {
            digits = new string('0', k - digits.Length + 1) + digits;
        }

        return digits.Substring(0, digits.Length - k) + "." + digits.Substring(digits.Length - k);
    }
}
