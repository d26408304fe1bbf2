using System;
using System.Numerics;
using System.Runtime.InteropServices;

namespace ParticlePhysics.Scenes.Text;

/// <summary>
/// Decimal text to the nearest double (ties to even), the same bits on every runtime: a scene loaded on Unity's Mono
/// must build the world .NET builds, and Mono's <c>double.Parse</c> and <c>Utf8Parser</c> are off by one unit in the
/// last place on some inputs (about 0.6 % of random 1- to 25-digit numbers, most of them of large or tiny exponent).
/// </summary>
/// <remarks>
/// The text is [+-] digits [. digits] [(e|E) [+-] digits], with at least one digit before or after the point; the
/// value is W 10^E for the integer W of its significant digits.
/// <list type="bullet">
/// <item>Fast path (Clinger 1990): W &lt;= 2^53 and |E| &lt;= 22. W and 10^|E| are then exact doubles, and one
/// correctly rounded multiplication or division gives the nearest double of W 10^E. Short numbers (a scene's
/// coordinates, an OBJ file's vertices) all take it.</item>
/// <item>Otherwise, exact integers: the value is N / M (N = W 10^E, M = 1, or N = W, M = 10^-E). Its binary exponent
/// is e2 = floor(log2(N / M)); the double's last place is 2^u with u = max(e2 - 52, -1074) (below -1022 the subnormals
/// keep fewer bits). The quotient q = floor(N 2^(1 - u) / M) holds the 53 (or fewer) kept bits and one more, the
/// remainder says whether anything lies below it, and rounding half to even of q / 2 is then exact.</item>
/// </list>
/// Values beyond double.MaxValue are refused (false); values below half the least subnormal round to a signed zero.
/// </remarks>
internal static class DecimalParser
{
    // 10^0 to 10^22: every one an exact double (10^22 = 2^22 5^22 and 5^22 < 2^53).
    private static readonly double[] _exactPowersOfTen =
    {
        1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19,
        1e20, 1e21, 1e22,
    };

    // Beyond these the value is certainly out of range or certainly rounds to zero, whatever the digits: with n digits
    // before the exponent, W 10^E lies in [10^(n - 1 + E), 10^(n + E)).
    private const int LargestDecimalExponent = 310; // 10^309 > double.MaxValue (1.8e308)
    private const int SmallestDecimalExponent = -325; // 10^-325 < 2^-1075, half the least subnormal

    /// <summary>Parses ASCII text (characters above 127 make it fail).</summary>
    /// <returns>False when the text is not a decimal number as above, or its value is beyond double.MaxValue.</returns>
    public static bool TryParse(ReadOnlySpan<char> input, out double value)
    {
        var text = ForReading(input);
        Span<byte> bytes = text.Length <= 256 ? stackalloc byte[text.Length] : new byte[text.Length];
        for (var i = 0; i < text.Length; i++)
        {
            if (text[i] > 127)
            {
                value = 0.0;
                return false;
            }

            bytes[i] = (byte)text[i];
        }

        return TryParse(bytes, out value);
    }

    /// <summary>Parses ASCII bytes (an OBJ file's token).</summary>
    /// <returns>False when the text is not a decimal number as above, or its value is beyond double.MaxValue.</returns>
    public static bool TryParse(ReadOnlySpan<byte> input, out double value)
    {
        var text = ForReading(input);
        value = 0.0;
        var i = 0;
        var negative = false;
        if (i < text.Length && (text[i] == '+' || text[i] == '-'))
        {
            negative = text[i] == '-';
            i++;
        }

        // The significand: its first 19 significant digits in an integer (19 digits always fit 64 bits), the count of
        // all of them, and the power of ten of its last digit.
        ulong leading = 0;
        var significant = 0;
        var mantissaDigits = 0;
        var firstSignificant = -1;
        var exponentShift = 0; // the decimal exponent of the last significant digit read, before the written exponent
        var point = false;
        for (; i < text.Length; i++)
        {
            var c = text[i];
            if (c == '.' && !point)
            {
                point = true;
                continue;
            }

            if (c < '0' || c > '9')
            {
                break;
            }

            mantissaDigits++;
            if (significant == 0 && c == '0')
            {
                if (point)
                {
                    exponentShift--;
                }

                continue;
            }

            if (significant == 0)
            {
                firstSignificant = i;
            }

            if (significant < 19)
            {
                leading = (leading * 10) + (ulong)(c - '0');
            }

            significant++;
            if (point)
            {
                exponentShift--;
            }
        }

        if (mantissaDigits == 0)
        {
            return false;
        }

        var mantissaEnd = i;
        long exponent = 0;
        if (i < text.Length && (text[i] == 'e' || text[i] == 'E'))
        {
            i++;
            var exponentNegative = false;
            if (i < text.Length && (text[i] == '+' || text[i] == '-'))
            {
                exponentNegative = text[i] == '-';
                i++;
            }

            var exponentDigits = 0;
            for (; i < text.Length && text[i] >= '0' && text[i] <= '9'; i++, exponentDigits++)
            {
                // Saturates far beyond any exponent that changes the outcome.
                exponent = Math.Min((exponent * 10) + (text[i] - '0'), 1_000_000_000L);
            }

            if (exponentDigits == 0)
            {
                return false;
            }

            exponent = exponentNegative ? -exponent : exponent;
        }

        if (i != text.Length)
        {
            return false;
        }

        if (significant == 0)
        {
            value = negative ? -0.0 : 0.0;
            return true;
        }

        // The digits after the first 19 were left out of the integer: they scale it by 10^(count).
        var dropped = significant - Math.Min(significant, 19);
        var decimalExponent = exponent + exponentShift + dropped; // value = W 10^decimalExponent with W the 19 digits...
        var magnitude = decimalExponent + Math.Min(significant, 19); // ...and lies below 10^magnitude
        if (magnitude > LargestDecimalExponent)
        {
            return false;
        }

        if (magnitude < SmallestDecimalExponent)
        {
            value = negative ? -0.0 : 0.0;
            return true;
        }

        double result;
        if (dropped == 0 && leading <= (1UL << 53) && decimalExponent >= -22 && decimalExponent <= 22)
        {
            result = decimalExponent >= 0
                ? leading * _exactPowersOfTen[decimalExponent]
                : leading / _exactPowersOfTen[-decimalExponent];
        }
        else
        {
            var whole = Significand(text, firstSignificant, mantissaEnd, significant);
            if (!TryNearest(whole, (int)(exponent + exponentShift), out result))
            {
                return false;
            }
        }

        value = negative ? -result : result;
        return true;
    }

    /// <summary>The integer of all <paramref name="count"/> significant digits from <paramref name="first"/> on.</summary>
    private static BigInteger Significand(Span<byte> text, int first, int end, int count)
    {
        var whole = BigInteger.Zero;
        ulong chunk = 0;
        var chunkDigits = 0;
        var read = 0;
        for (var i = first; i < end && read < count; i++)
        {
            var c = text[i];
            if (c == '.')
            {
                continue;
            }

            chunk = (chunk * 10) + (ulong)(c - '0');
            chunkDigits++;
            read++;
            if (chunkDigits == 18)
            {
                whole = (whole * 1_000_000_000_000_000_000UL) + chunk;
                chunk = 0;
                chunkDigits = 0;
            }
        }

        return chunkDigits == 0 ? whole : (whole * BigInteger.Pow(10, chunkDigits)) + chunk;
    }

    /// <summary>The nearest double to <paramref name="whole"/> 10^<paramref name="exponent"/> (ties to even), if finite.</summary>
    private static bool TryNearest(BigInteger whole, int exponent, out double value)
    {
        value = 0.0;
        BigInteger n, m;
        if (exponent >= 0)
        {
            n = whole * BigInteger.Pow(10, exponent);
            m = BigInteger.One;
        }
        else
        {
            n = whole;
            m = BigInteger.Pow(10, -exponent);
        }

        // e2 = floor(log2(n / m)): n / m lies in [2^(b - 1), 2^(b + 1)) for b the difference of their bit lengths.
        var b = BitLength(n) - BitLength(m);
        var atLeast = b >= 0 ? n >= (m << b) : (n << -b) >= m;
        var e2 = atLeast ? b : b - 1;
        if (e2 > 1023)
        {
            return false;
        }

        var u = Math.Max(e2 - 52, -1074);
        var shift = 1 - u;
        var quotient = shift >= 0
            ? BigInteger.DivRem(n << shift, m, out var remainder)
            : BigInteger.DivRem(n, m << -shift, out remainder);
        var q = (ulong)quotient; // below 2^54
        var kept = q >> 1;
        if ((q & 1) != 0 && (!remainder.IsZero || (kept & 1) != 0))
        {
            kept++;
        }

        if (kept == 1UL << 53)
        {
            kept = 1UL << 52;
            u++;
        }

        if (kept >= 1UL << 52)
        {
            var biased = u + 52 + 1023;
            if (biased >= 2047)
            {
                return false;
            }

            value = BitConverter.Int64BitsToDouble((long)(((ulong)biased << 52) | (kept - (1UL << 52))));
        }
        else
        {
            value = BitConverter.Int64BitsToDouble((long)kept); // a subnormal: u is -1074
        }

        return true;
    }

    /// <summary>
    /// The same memory as a span, only read: Mono's ReadOnlySpan indexer returns ref T where the netstandard2.1
    /// reference says ref readonly T, so indexing a ReadOnlySpan does not bind there (as in the core's ReadOnlySpans).
    /// </summary>
    private static Span<T> ForReading<T>(ReadOnlySpan<T> span) =>
        MemoryMarshal.CreateSpan(ref MemoryMarshal.GetReference(span), span.Length);

    /// <summary>The number of bits of a positive integer (netstandard2.1 has no BigInteger.GetBitLength).</summary>
    private static int BitLength(BigInteger positive)
    {
        var bytes = positive.ToByteArray(); // little-endian two's complement: a positive number's top byte may be 0
        var top = bytes.Length - 1;
        while (top > 0 && bytes[top] == 0)
        {
            top--;
        }

        var bits = 8 * top;
        for (int last = bytes[top]; last != 0; last >>= 1)
        {
            bits++;
        }

        return bits;
    }
}
