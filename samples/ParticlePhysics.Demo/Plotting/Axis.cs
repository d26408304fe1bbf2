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
            var low = Math.Floor(Math.Log10(min));
            var high = Math.Max(low + 1, Math.Ceiling(Math.Log10(max)));
            var stride = Math.Max(1, (int)Math.Ceiling((high - low) / 8));
            var ticks = new List<double>();
            for (var e = low; e <= high; e += stride)
            {
                ticks.Add(Math.Pow(10, e));
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

    /// <summary>Where <paramref name="value"/> falls, from 0 (low end) to 1 (high end).</summary>
    public double Fraction(double value) =>
        Logarithmic ? (Math.Log10(value) - _low) / (_high - _low) : (value - _low) / (_high - _low);

    /// <summary>A tick's label: "1e-4" on a log axis, a short number on a linear one.</summary>
    public string Label(double tick) =>
        Logarithmic
            ? FormattableString.Invariant($"1e{Math.Round(Math.Log10(tick))}")
            : Math.Abs(tick) < 1e-12 * Math.Max(Math.Abs(_low), Math.Abs(_high)) ? "0" : tick.ToString("G4", System.Globalization.CultureInfo.InvariantCulture);

    /// <summary>A step of 1, 2 or 5 times a power of ten, near <paramref name="rough"/>.</summary>
    private static double NiceStep(double rough)
    {
        var power = Math.Pow(10, Math.Floor(Math.Log10(rough)));
        var mantissa = rough / power;
        return (mantissa < 1.5 ? 1 : mantissa < 3.5 ? 2 : mantissa < 7.5 ? 5 : 10) * power;
    }
}
