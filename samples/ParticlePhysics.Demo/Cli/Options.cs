using System;
using System.CommandLine;
using System.CommandLine.Parsing;
using System.Globalization;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Demo.Cli;

/// <summary>
/// Builds options whose values are read in the invariant culture (so "--dt 0.01" works under a French locale too)
/// and checked at parse time, each bad value reported as one sentence naming the option, the value and what is allowed.
/// </summary>
internal static class Options
{
    /// <summary>A number option with a default shown in the help.</summary>
    public static Option<double> Number(string name, string description, string unit, double defaultValue, NumberRule rule) =>
        new(name)
        {
            Description = Describe(description, unit),
            HelpName = unit.Length == 0 ? "number" : unit,
            DefaultValueFactory = _ => defaultValue,
            CustomParser = result => ParseNumber(result, name, unit, rule) ?? defaultValue,
        };

    /// <summary>A number option without a fixed default (the description says what happens when it is left out).</summary>
    /// <summary>The <c>--gravity</c> option every scenario shares: g in m/s^2, pointing down (-y), a finite number &gt;= 0.</summary>
    public static Option<double> Gravity(double defaultValue) =>
        Number("--gravity", "Gravity g (pointing down, -y)", "m/s^2", defaultValue, NumberRule.NonNegative);

    public static Option<double?> OptionalNumber(string name, string description, string unit, NumberRule rule) =>
        new(name)
        {
            Description = Describe(description, unit),
            HelpName = unit.Length == 0 ? "number" : unit,
            CustomParser = result => ParseNumber(result, name, unit, rule),
        };

    /// <summary>A whole-number option from <paramref name="minimum"/> to <paramref name="maximum"/>.</summary>
    public static Option<int?> Count(string name, string description, int minimum, int? defaultValue = null, int maximum = int.MaxValue)
    {
        var option = new Option<int?>(name)
        {
            Description = description,
            HelpName = "N",
            CustomParser = result =>
            {
                var text = result.Tokens.Count > 0 ? result.Tokens[0].Value : null;
                if (text is null)
                {
                    return defaultValue;
                }

                if (!int.TryParse(text, NumberStyles.Integer, CultureInfo.InvariantCulture, out var value) || value < minimum || value > maximum)
                {
                    result.AddError($"{name} must be a whole number from {minimum} to {maximum}; got '{text}'.");
                    return null;
                }

                return value;
            },
        };
        if (defaultValue is { } d)
        {
            option.DefaultValueFactory = _ => d;
        }

        return option;
    }

    /// <summary>A choice among <paramref name="allowed"/>.</summary>
    public static Option<string> Choice(string name, string description, string defaultValue, params string[] allowed)
    {
        var option = new Option<string>(name)
        {
            Description = description,
            HelpName = string.Join('|', allowed),
            DefaultValueFactory = _ => defaultValue,
        };
        option.Validators.Add(result =>
        {
            var value = result.GetValueOrDefault<string>();
            if (Array.IndexOf(allowed, value) < 0)
            {
                result.AddError($"unknown {name.TrimStart('-')} '{value}'{Suggestions.DidYouMean(value, allowed)}; expected one of: {string.Join(", ", allowed)}.");
            }
        });
        return option;
    }

    private static string Describe(string description, string unit) =>
        unit.Length == 0 ? description : $"{description}, in {unit}";

    private static double? ParseNumber(ArgumentResult result, string name, string unit, NumberRule rule)
    {
        if (result.Tokens.Count == 0)
        {
            return null;
        }

        var text = result.Tokens[0].Value;
        var parsed = TryParseNumber(text, out var value);
        var ok = parsed && double.IsFinite(value) && rule switch
        {
            NumberRule.Positive => value > 0,
            NumberRule.Mass => value > 0 && double.IsFinite(1 / value),
            NumberRule.Tolerance => value >= DormandPrince45.MinTolerance,
            NumberRule.NonNegative => value >= 0,
            NumberRule.Fraction => value >= 0 && value <= 1,
            _ => true,
        };
        if (!ok)
        {
            var allowed = rule switch
            {
                NumberRule.Positive => "a positive finite number",
                NumberRule.Mass => "a positive finite number >= 5.6e-309 (1/m must be finite)",
                NumberRule.Tolerance => $"a finite number >= {DormandPrince45.MinTolerance.ToString("R", CultureInfo.InvariantCulture)} (100 machine epsilons)",
                NumberRule.NonNegative => "a finite number >= 0",
                NumberRule.Fraction => "a number from 0 to 1",
                _ => "a finite number",
            };
            var units = unit.Length == 0 ? string.Empty : $" ({unit})";
            result.AddError($"{name} must be {allowed}{units}, as a decimal or a fraction such as 1/127; got '{text}'.");
            return null;
        }

        return value;
    }

    /// <summary>
    /// A number in the invariant culture, or a fraction p/q of two such numbers (so that --resolution 1/127 gives
    /// the spacing of a 128 x 128 cloth exactly as the division does).
    /// </summary>
    internal static bool TryParseNumber(string text, out double value)
    {
        var slash = text.IndexOf('/', StringComparison.Ordinal);
        if (slash < 0)
        {
            return double.TryParse(text, NumberStyles.Float, CultureInfo.InvariantCulture, out value);
        }

        value = double.NaN;
        if (!double.TryParse(text.AsSpan(0, slash), NumberStyles.Float, CultureInfo.InvariantCulture, out var numerator)
            || !double.TryParse(text.AsSpan(slash + 1), NumberStyles.Float, CultureInfo.InvariantCulture, out var denominator)
            || denominator == 0)
        {
            return false;
        }

        value = numerator / denominator;
        return true;
    }
}
