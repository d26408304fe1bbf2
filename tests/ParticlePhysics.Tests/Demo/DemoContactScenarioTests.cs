using System;
using System.Globalization;
using System.IO;
using System.Linq;

namespace ParticlePhysics.Tests.Demo;

/// <summary>The contact scenarios of the contract: bouncing-ball, collision and drape, with their summaries, columns, plots and errors.</summary>
public class DemoContactScenarioTests
{
    [Fact]
    public void The_bouncing_ball_table_lists_its_apexes_against_e_to_the_2n_h()
    {
        var result = DemoProcess.Run("bouncing-ball");
        Assert.True(result.ExitCode == 0, result.Error);
        var lines = result.OutputLines;
        var header = Array.FindIndex(lines, l => l.StartsWith("bounce ", StringComparison.Ordinal));
        Assert.True(header > 0, result.Output);
        for (var n = 1; n <= 6; n++)
        {
            var cells = lines[header + 1 + n].Split(' ', StringSplitOptions.RemoveEmptyEntries);
            Assert.Equal(n.ToString(CultureInfo.InvariantCulture), cells[0]);
            var apex = double.Parse(cells[4], CultureInfo.InvariantCulture);
            Assert.Equal(Math.Pow(0.8, 2 * n), apex, 5);
            Assert.True(double.Parse(cells[5], CultureInfo.InvariantCulture) < 1e-12, lines[header + 1 + n]);
        }

        Assert.Contains(lines, l => l.StartsWith("final state at t = 5 s: y0 = 0, vy0 = 0", StringComparison.Ordinal));
        Assert.Contains(lines, l => l.Contains("at rest from t = 4.05", StringComparison.Ordinal) && l.Contains("exact T = t1 (1 + e) / (1 - e) = 4.06371 s", StringComparison.Ordinal));
    }

    [Fact]
    public void The_bouncing_ball_takes_its_options_and_tracks_the_exact_solution_in_csv()
    {
        var result = DemoProcess.Run("bouncing-ball", "--radius", "0.1", "--height", "2", "--restitution", "0.5", "--friction", "0.1", "--vx0", "3", "--format", "csv", "--every", "100");
        Assert.True(result.ExitCode == 0, result.Error);
        var (header, rows) = result.Csv();
        Assert.Equal(new[] { "t", "x0", "y0", "z0", "vx0", "vy0", "vz0", "y0_exact", "vy0_exact", "error", "energy" }, header);
        Assert.Equal(2.0, rows[0][2]);
        Assert.Equal(3.0, rows[0][4]);
        Assert.All(rows, r => Assert.True(r[9] < 1e-3, $"error {r[9]} at t = {r[0]}"));
        Assert.Equal(0.1, rows[^1][2], 12);
    }

    [Fact]
    public void With_drag_the_bouncing_ball_has_no_exact_columns()
    {
        var result = DemoProcess.Run("bouncing-ball", "--drag", "0.1", "--duration", "1");
        Assert.True(result.ExitCode == 0, result.Error);
        Assert.Contains("no exact solution with drag", result.Output, StringComparison.Ordinal);
        Assert.DoesNotContain("y0_exact", result.Output, StringComparison.Ordinal);
    }

    [Fact]
    public void The_collision_reports_the_contact_time_and_exact_velocities()
    {
        var result = DemoProcess.Run("collision", "--m1", "1", "--m2", "3", "--restitution", "0.5", "--v1", "2", "--v2", "0");
        Assert.True(result.ExitCode == 0, result.Error);
        Assert.Contains("contact at t = 0.9 s (exact t* = (2 - 2 r) / (v1 - v2) = 0.9 s)", result.Output, StringComparison.Ordinal);
        Assert.Contains("leaving with v1' = -0.25, v2' = 0.75 m/s exact", result.Output, StringComparison.Ordinal);
        Assert.Contains("vx0 = -0.25, x1 = 1.825, vx1 = 0.75", result.Output, StringComparison.Ordinal);

        var csv = DemoProcess.Run("collision", "--format", "csv", "--gravity", "9.81");
        var (header, rows) = csv.Csv();
        Assert.Equal(new[] { "t", "x0", "y0", "z0", "vx0", "vy0", "vz0", "x1", "y1", "z1", "vx1", "vy1", "vz1", "x0_exact", "vx0_exact", "x1_exact", "vx1_exact", "error", "energy" }, header);
        Assert.All(rows, r => Assert.True(r[17] < 1e-9, $"error {r[17]} at t = {r[0]}"));
    }

    [Fact]
    public void The_drape_keeps_every_particle_out_of_the_sphere()
    {
        var result = DemoProcess.Run("drape", "--duration", "0.5", "--format", "csv", "--every", "50");
        Assert.True(result.ExitCode == 0, result.Error);
        var (header, rows) = result.Csv();
        var gap = Array.IndexOf(header, "sphere_gap");
        Assert.True(gap > 0);
        Assert.Equal("middle_y", header[^1]);
        Assert.All(rows, r => Assert.True(r[gap] >= -1e-6, $"gap {r[gap]} at t = {r[0]}"));
        Assert.Equal(-0.19, rows[^1][^1], 6);

        var table = DemoProcess.Run("drape", "--duration", "0.3", "--sphere-radius", "0.2", "--sphere-y", "-0.3", "--friction", "0.1", "--radius", "0.02");
        Assert.True(table.ExitCode == 0, table.Error);
        Assert.Contains("deepest into the sphere over the run:", table.Output, StringComparison.Ordinal);
    }

    [Fact]
    public void Plots_of_the_contact_scenarios_are_written()
    {
        foreach (var scenario in new[] { "bouncing-ball", "collision", "drape" })
        {
            var path = Path.Combine(Path.GetTempPath(), $"contacts-{scenario}-{Guid.NewGuid():N}.svg");
            try
            {
                var result = DemoProcess.Run(scenario, "--duration", "0.5", "--plot", path);
                Assert.True(result.ExitCode == 0, result.Error);
                var svg = File.ReadAllText(path);
                Assert.StartsWith("<?xml", svg, StringComparison.Ordinal);
                Assert.Contains(scenario, svg, StringComparison.Ordinal);
                Assert.True(svg.Count(c => c == '\n') > 10);
            }
            finally
            {
                File.Delete(path);
            }
        }
    }

    [Theory]
    [InlineData("bouncing-ball --restitution 1.5", "--restitution", "1.5", "0 to 1")]
    [InlineData("bouncing-ball --restitution -0.1", "--restitution", "-0.1")]
    [InlineData("bouncing-ball --friction -0.2", "--friction", "-0.2", ">= 0")]
    [InlineData("bouncing-ball --radius -1", "--radius", "-1")]
    [InlineData("bouncing-ball --height 0.05 --radius 0.1", "--height", "0.05", "--radius")]
    [InlineData("collision --radius 1", "--radius", "1", "less than 1")]
    [InlineData("collision --restitution 2", "--restitution", "2")]
    [InlineData("collision --m1 0", "--m1", "'0'")]
    [InlineData("drape --friction -1", "--friction", "-1")]
    [InlineData("drape --radius -0.01", "--radius", "-0.01")]
    [InlineData("drape --sphere-radius 0", "--sphere-radius", "'0'")]
    [InlineData("drape --resolution 0.3", "--resolution", "0.3", "--size")]
    [InlineData("drape --pin some", "some", "corners, edge, none")]
    public void Bad_contact_options_are_refused_with_one_error_line_and_exit_code_2(string commandLine, params string[] mentioned)
    {
        var result = DemoProcess.Run(commandLine.Split(' '));
        Assert.True(result.ExitCode == 2, $"exit code {result.ExitCode}, stderr: {result.Error}");
        Assert.Equal("", result.Output);
        var line = Assert.Single(result.ErrorLines);
        Assert.StartsWith("error: ", line, StringComparison.Ordinal);
        foreach (var text in mentioned)
        {
            Assert.Contains(text, line, StringComparison.Ordinal);
        }
    }
}
