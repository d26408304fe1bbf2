using System;
using System.IO;
using System.Linq;
using System.Text.Json;

namespace ParticlePhysics.Tests.Demo;

/// <summary>
/// Ctrl-C (here: a cancellation already requested when the run starts) stops a run between two steps: whatever
/// the format, the output so far stays and ends properly, one line on stderr says so, and the exit code is 130.
/// The real key on a real terminal is tested by <see cref="DemoTerminalTests"/>.
/// </summary>
public sealed class DemoInterruptTests : IDisposable
{
    private readonly string _folder = Directory.CreateTempSubdirectory("pp-demo-interrupt-").FullName;

    public void Dispose() => Directory.Delete(_folder, recursive: true);

    [Fact]
    public void An_interrupted_csv_run_keeps_its_header_and_rows()
    {
        var result = DemoProcess.RunInterrupted("free-fall", "--format", "csv");

        Assert.Equal(130, result.ExitCode);
        var (header, rows) = result.Csv();
        Assert.Equal("t", header[0]);
        Assert.Equal(new[] { 0.0 }, rows.Select(r => r[0]));
        Assert.Equal("interrupted by Ctrl-C at t = 0 s (step 0 of 1000); the rows printed so far were kept.", result.ErrorLines.Single());
    }

    [Fact]
    public void An_interrupted_json_run_is_still_a_whole_document_that_says_so()
    {
        var result = DemoProcess.RunInterrupted("cloth", "--format", "json");

        Assert.Equal(130, result.ExitCode);
        using var document = JsonDocument.Parse(result.Output);
        Assert.True(document.RootElement.GetProperty("interrupted").GetBoolean());
        Assert.Equal(JsonValueKind.Null, document.RootElement.GetProperty("diverged").ValueKind);
        Assert.Equal(0, document.RootElement.GetProperty("summary").GetProperty("step").GetInt32());
    }

    [Fact]
    public void An_interrupted_table_says_where_it_stopped_and_the_plot_and_page_are_written()
    {
        var plot = Path.Combine(_folder, "cloth.svg");
        var page = Path.Combine(_folder, "cloth.html");

        var result = DemoProcess.RunInterrupted("cloth", "--plot", plot, "--animate", page);

        Assert.Equal(130, result.ExitCode);
        Assert.StartsWith("interrupted (Ctrl-C) at t = 0 s; state there: min_y = 0", result.OutputLines[^1], StringComparison.Ordinal);
        Assert.True(File.Exists(plot));
        Assert.Contains("\"status\":\"interrupted\"", File.ReadAllText(page), StringComparison.Ordinal);
    }

    [Fact]
    public void An_interrupted_tour_and_convergence_stop_with_130()
    {
        var tour = DemoProcess.RunInterrupted();
        var convergence = DemoProcess.RunInterrupted("convergence", "free-fall");

        Assert.Equal(130, tour.ExitCode);
        Assert.Equal("interrupted by Ctrl-C; the table holds the runs that had finished.", tour.ErrorLines.Single());
        Assert.Equal(130, convergence.ExitCode);
        Assert.Equal("interrupted by Ctrl-C; the rows printed were computed in full, the rest were not run.", convergence.ErrorLines.Single());
    }
}
