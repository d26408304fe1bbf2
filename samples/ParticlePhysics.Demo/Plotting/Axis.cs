using System;
using System.Collections.Generic;
using System.Linq;

namespace ParticlePhysics.Demo.Plotting;

/// <summary>A linear or logarithmic axis: its data range, its ticks and their labels, and the map to pixels.</summary>
internal sealed class Axis
{
    private readonly double _low;
    private readonly double _high;

    private Axis(double low, double high, bool logarithmic, IReadOnlyList<double> ticks)
    {
        _low = low;
        _high = high;
        Logarithmic = logarithmic;
        Ticks = ticks;
    }

    public bool Logarithmic { get; }

    public IReadOnlyList<double> Ticks { get; }

    /// <summary>An axis covering <paramref name="values"/> (non-finite values, and non-positive ones on a log axis, are ignored).</summary>
    public static Axis Covering(IEnumerable<double> values, bool logarithmic)
    {
        var usable = values.Where(v => double.IsFinite(v) && (!logarithmic || v > 0)).ToArray();
        if (usable.Length == 0)
        {
            usable = logarithmic ? new[] { 1.0, 10.0 } : new[] { 0.0, 1.0 };
        }

        double min = usable.Min(), max = usable.Max();
        if (logarithmic)
        {
            // Tight to the data, padded by a few per cent of its span in decades; ticks at the decades, and at 2 and 5
            // times them when the axis spans few decades.
            double lowLog = Math.Log10(min), highLog = Math.Log10(max);
            var pad = Math.Max(0.05, 0.06 * (highLog - lowLog));
            var (low, high) = (lowLog - pad, highLog + pad);
            var ticks = new List<double>();
            var stride = Math.Max(1, (int)Math.Ceiling((high - low) / 9));
            var mantissas = high - low < 2.5 ? new[] { 1.0, 2.0, 5.0 } : new[] { 1.0 };
            for (var e = (int)Math.Floor(low); e <= (int)Math.Ceiling(high); e++)
            {
                if (e % stride != 0)
                {
                    continue;
                }

                foreach (var m in mantissas)
                {
                    var tick = m * Math.Pow(10, e);
                    var at = Math.Log10(tick);
                    if (at >= low - 1e-9 && at <= high + 1e-9)
                    {
                        ticks.Add(tick);
                    }
                }
            }

            return new Axis(low, high, true, ticks);
        }

        if (max - min < 1e-12 * Math.Max(1, Math.Abs(max)))
        {
            var pad = Math.Max(1e-3, Math.Abs(max) * 0.1);
            (min, max) = (min - pad, max + pad);
        }

        var step = NiceStep((max - min) / 6);
        var start = Math.Floor(min / step) * step;
        var end = Math.Ceiling(max / step) * step;
        var linear = new List<double>();
        for (var k = 0; start + (k * step) <= end + (step * 1e-9); k++)
        {
            linear.Add(start + (k * step));
        }

        return new Axis(start, end, false, linear);
    }

    /// <summary>The value at the low end of the axis.</summary>
    public double Low => At(0);

    /// <summary>The value at the high end of the axis.</summary>
    public double High => At(1);

    /// <summary>The value at <paramref name="fraction"/> of the way from the low end (0) to the high end (1).</summary>
    public double At(double fraction) =>
        Logarithmic ? Math.Pow(10, _low + (fraction * (_high - _low))) : _low + (fraction * (_high - _low));

    /// <summary>Where <paramref name="value"/> falls, from 0 (low end) to 1 (high end).</summary>
    public double Fraction(double value) =>
        Logarithmic ? (Math.Log10(value) - _low) / (_high - _low) : (value - _low) / (_high - _low);

    /// <summary>
    /// A tick's label: on a log axis "0.002" when every tick is between 1e-4 and 1e4, else "2e-7"; a short number on a
    /// linear one.
    /// </summary>
    public string Label(double tick)
    {
        if (!Logarithmic)
        {
            return Math.Abs(tick) < 1e-12 * Math.Max(Math.Abs(_low), Math.Abs(_high)) ? "0" : tick.ToString("G4", System.Globalization.CultureInfo.InvariantCulture);
        }

        if (Ticks.All(t => t >= 1e-4 && t < 1e4))
        {
            return tick.ToString("G4", System.Globalization.CultureInfo.InvariantCulture);
        }

        var exponent = (int)Math.Floor(Math.Log10(tick) + 1e-9);
        var mantissa = Math.Round(tick / Math.Pow(10, exponent));
        return exponent == 0 ? FormattableString.Invariant($"{mantissa}") : FormattableString.Invariant($"{mantissa}e{exponent}");
    }

    /// <summary>Ticks at a step of 1, 2 or 5 times a power of ten (about <paramref name="count"/> of them) between low and high.</summary>
    public static double[] LinearTicks(double low, double high, int count)
    {
        var step = NiceStep(Math.Max(high - low, 1e-12) / count);
        var ticks = new List<double>();
        for (var k = Math.Ceiling((low / step) - 1e-9); k * step <= high + (1e-9 * step); k++)
        {
            ticks.Add(Math.Abs(k) < 0.5 ? 0 : k * step);
        }

        return ticks.ToArray();
    }

    /// <summary>A step of 1, 2 or 5 times a power of ten, near <paramref name="rough"/>.</summary>
    public static double NiceStep(double rough)
    {
        var power = Math.Pow(10, Math.Floor(Math.Log10(rough)));
        var mantissa = rough / power;
        return (mantissa < 1.5 ? 1 : mantissa < 3.5 ? 2 : mantissa < 7.5 ? 5 : 10) * power;
    }
}
