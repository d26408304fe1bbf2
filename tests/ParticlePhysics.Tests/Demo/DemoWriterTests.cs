using System;
using System.Globalization;
using System.IO;
using System.Text.Json;
using ParticlePhysics.Demo;
using ParticlePhysics.Demo.Output;
using ParticlePhysics.Demo.Running;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Tests.Demo;

/// <summary>The writers on their own: values no real run produces, and the terminal-only progress line.</summary>
public class DemoWriterTests
{
    [Fact]
    public void Json_never_holds_a_raw_NaN_or_infinity()
    {
        var setup = new ScalarOdeSetup(new GaussianDecayOde());
        var plan = new RunPlan("rk4", 0.1, 1, 1, 1e-8);
        using var text = new StringWriter(CultureInfo.InvariantCulture);
        var writer = new JsonRunWriter(text);

        writer.Begin(setup, plan);
        writer.WriteRow(new[] { 0, double.NaN, double.PositiveInfinity, double.NegativeInfinity });
        writer.End(new RunOutcome(new[] { 0.1, double.NaN, 1, double.NaN }, 1, 0.1, double.NaN, null));

        using var document = JsonDocument.Parse(text.ToString());
        var row = document.RootElement.GetProperty("rows")[0];
        Assert.Equal(JsonValueKind.Null, row[1].ValueKind);
        Assert.Equal(JsonValueKind.Null, row[2].ValueKind);
        Assert.Equal(JsonValueKind.Null, row[3].ValueKind);
        Assert.Equal(JsonValueKind.Null, document.RootElement.GetProperty("summary").GetProperty("error").ValueKind);
    }

    [Fact]
    public void Csv_numbers_are_invariant_and_shortest_round_trip_under_any_culture()
    {
        var saved = CultureInfo.CurrentCulture;
        try
        {
            CultureInfo.CurrentCulture = CultureInfo.GetCultureInfo("de-DE");
            Assert.Equal("0.1", Numbers.RoundTrip(0.1));
            Assert.Equal("0.30000000000000004", Numbers.RoundTrip(0.1 + 0.2));
            Assert.Equal("1E-05", Numbers.RoundTrip(1e-5));
            Assert.Equal("0", Numbers.RoundTrip(-0.0));
            Assert.Equal(0.1 + 0.2, double.Parse(Numbers.RoundTrip(0.1 + 0.2), CultureInfo.InvariantCulture));
        }
        finally
        {
            CultureInfo.CurrentCulture = saved;
        }
    }

    [Fact]
    public void A_short_run_shows_no_progress_line_even_on_a_terminal()
    {
        using var output = new StringWriter(CultureInfo.InvariantCulture);
        using var error = new StringWriter(CultureInfo.InvariantCulture);

        var code = Program.Run(new[] { "free-fall", "--format", "csv" }, output, error, errorIsTerminal: true);

        Assert.Equal(0, code);
        Assert.Equal("", error.ToString()); // the indicator stays silent for the first second
        Assert.StartsWith("t,x0,", output.ToString(), StringComparison.Ordinal);
    }
}
