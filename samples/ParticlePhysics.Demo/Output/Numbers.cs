using System.Globalization;

namespace ParticlePhysics.Demo.Output;

/// <summary>How numbers are printed: exactly for programs, briefly for people; always in the invariant culture.</summary>
internal static class Numbers
{
    /// <summary>The shortest text that reads back to the same double ("R" in .NET Core 3+), invariant culture.</summary>
    /// <remarks>Negative zero prints as 0: "-0" is exact but only confuses a reader (an exact velocity -g t at t = 0).</remarks>
    public static string RoundTrip(double value) => (value == 0 ? 0.0 : value).ToString("R", CultureInfo.InvariantCulture);

    /// <summary>Six significant digits, for tables people read (enough to see a 300 m fall move by centimetres).</summary>
    public static string Brief(double value) => (value == 0 ? 0.0 : value).ToString("G6", CultureInfo.InvariantCulture);

    /// <summary>Three significant digits in exponent form, for errors that span many decades.</summary>
    public static string Error(double value) => value.ToString("0.00E+00", CultureInfo.InvariantCulture);

    /// <summary>A JSON number, or null for NaN and infinities (which JSON cannot hold).</summary>
    public static string Json(double value) => double.IsFinite(value) ? RoundTrip(value) : "null";
}
