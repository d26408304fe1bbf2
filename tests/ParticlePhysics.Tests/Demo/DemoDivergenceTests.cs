using System;
using System.Linq;
using System.Text.Json;

namespace ParticlePhysics.Tests.Demo;

/// <summary>A run that diverges keeps its rows, says where it stopped on one line of stderr, and exits with code 3.</summary>
public class DemoDivergenceTests
{
    private static readonly string[] _oneFrameCloth = { "cloth", "--dt", "0.0166667", "--every", "1" };

    [Fact]
    public void A_cloth_at_one_60_hz_frame_per_step_diverges_with_rk4_keeps_its_rows_and_exits_with_3()
    {
        var result = DemoProcess.Run(_oneFrameCloth.Append("--format").Append("csv").ToArray());

        Assert.Equal(3, result.ExitCode);
        var (header, rows) = result.Csv();
        Assert.Equal("t", header[0]);
        Assert.True(rows.Length > 5, $"the rows before the divergence are kept; got {rows.Length}");
        Assert.All(rows, r => Assert.All(r, v => Assert.True(double.IsFinite(v))));
        Assert.Equal(Enumerable.Range(0, rows.Length).Select(s => s * 0.0166667), rows.Select(r => r[0]));

        var line = Assert.Single(result.ErrorLines);
        Assert.StartsWith("error: simulation diverged at t=", line, StringComparison.Ordinal);
        Assert.Contains((rows.Length * 0.0166667).ToString("R", System.Globalization.CultureInfo.InvariantCulture), line, StringComparison.Ordinal);
        Assert.Contains("--dt", line, StringComparison.Ordinal);
        Assert.Contains("--integrator", line, StringComparison.Ordinal);
    }

    [Fact]
    public void A_diverged_json_run_is_still_valid_json_with_its_rows_and_the_divergence()
    {
        var result = DemoProcess.Run(_oneFrameCloth.Append("--format").Append("json").ToArray());

        Assert.Equal(3, result.ExitCode);
        using var document = JsonDocument.Parse(result.Output);
        var root = document.RootElement;
        Assert.True(root.GetProperty("rows").GetArrayLength() > 5);
        Assert.Equal(JsonValueKind.Object, root.GetProperty("diverged").ValueKind);
        Assert.True(root.GetProperty("diverged").GetProperty("t").GetDouble() > 0.1);
    }

    [Fact]
    public void A_diverged_table_run_keeps_its_rows_and_says_where_it_stopped()
    {
        var result = DemoProcess.Run(_oneFrameCloth);

        Assert.Equal(3, result.ExitCode);
        Assert.True(result.OutputLines.Length > 8);
        Assert.StartsWith("diverged at t = ", result.OutputLines[^1], StringComparison.Ordinal);
        Assert.StartsWith("error: simulation diverged", Assert.Single(result.ErrorLines), StringComparison.Ordinal);
    }

    [Fact]
    public void A_free_fall_from_1e12_m_runs_to_the_end_and_matches_its_exact_solution()
    {
        // Issue 10, item 11: the contract allows any finite height; this one "diverged" at step 1 (exit 3).
        var result = DemoProcess.Run("free-fall", "--height", "1.1e12", "--format", "csv");

        Assert.Equal(0, result.ExitCode);
        Assert.Equal("", result.Error);
        var (header, rows) = result.Csv();
        var last = rows[^1];
        Assert.Equal(10.0, last[0], 12);
        Assert.Equal(last[Array.IndexOf(header, "y0_exact")], last[Array.IndexOf(header, "y0")], 1.0);
    }

    [Fact]
    public void A_divergence_says_which_speed_passed_the_limit()
    {
        var result = DemoProcess.Run(_oneFrameCloth.Append("--format").Append("csv").ToArray());

        Assert.Equal(3, result.ExitCode);
        Assert.Matches(@"particle \d+ reached v[xyz] = \S+ m/s, beyond the divergence limit 1E\+12 m/s", result.Error);
    }

    [Fact]
    public void The_same_cloth_at_its_default_step_does_not_diverge()
    {
        var result = DemoProcess.Run("cloth", "--duration", "0.5", "--format", "csv");

        Assert.Equal(0, result.ExitCode);
        Assert.Equal("", result.Error);
    }
}
