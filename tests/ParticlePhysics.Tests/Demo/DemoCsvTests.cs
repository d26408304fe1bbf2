using System;
using System.Globalization;
using System.Linq;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Tests.Demo;

/// <summary>The csv format: header, row selection (step 0, every N-th, the last), times as step * dt, and the locale.</summary>
public class DemoCsvTests
{
    [Fact]
    public void Free_fall_csv_has_the_contract_header_then_the_extra_columns()
    {
        var result = DemoProcess.Run("free-fall", "--format", "csv", "--duration", "0.1");

        Assert.Equal(0, result.ExitCode);
        Assert.Equal("", result.Error);
        var (header, _) = result.Csv();
        Assert.Equal(new[] { "t", "x0", "y0", "z0", "vx0", "vy0", "vz0" }, header.Take(7));
        Assert.Equal(new[] { "y0_exact", "vy0_exact", "error", "energy" }, header.Skip(7));
    }

    [Fact]
    public void Two_mass_chain_csv_has_six_state_columns_per_particle_in_creation_order()
    {
        var (header, rows) = DemoProcess.Run("two-mass-chain", "--format", "csv", "--duration", "0.05").Csv();

        Assert.Equal("t,x0,y0,z0,vx0,vy0,vz0,x1,y1,z1,vx1,vy1,vz1", string.Join(',', header.Take(13)));
        Assert.All(rows, r => Assert.Equal(header.Length, r.Length));
        Assert.Equal(-1.0, rows[0][2]); // particle 0 starts at (0, -L1, 0)
        Assert.Equal(-1.0, rows[0][8]); // particle 1 at (0, -L1 - L2, 0) with L2 = 0
    }

    [Fact]
    public void Scalar_ode_columns_are_exactly_t_y_exact_error()
    {
        var result = DemoProcess.Run("scalar-ode", "--format", "csv");

        Assert.Equal("t,y,exact,error", result.OutputLines[0]);
        Assert.Equal(21, result.OutputLines.Length - 1); // dt 0.1 over 2 s: steps 0..20
    }

    [Fact]
    public void Rows_are_step_zero_every_nth_step_and_the_last_with_t_printed_as_step_times_dt()
    {
        // 0.25 / 0.01 = 25 steps; --every 10 gives steps 0, 10, 20 and the last, 25.
        var result = DemoProcess.Run("free-fall", "--format", "csv", "--duration", "0.25", "--every", "10");

        var times = result.OutputLines.Skip(1).Select(l => l.Split(',')[0]).ToArray();
        Assert.Equal(new[] { "0", "0.1", "0.2", "0.25" }, times);
    }

    [Fact]
    public void Times_are_step_times_dt_not_a_running_sum()
    {
        var result = DemoProcess.Run("free-fall", "--format", "csv", "--duration", "1", "--every", "1");

        var times = result.OutputLines.Skip(1).Select(l => l.Split(',')[0]).ToArray();
        Assert.Equal(101, times.Length);
        for (var step = 0; step <= 100; step++)
        {
            Assert.Equal((step * 0.01).ToString("R", CultureInfo.InvariantCulture), times[step]);
        }

        Assert.Contains("0.3", times); // a running sum would print 0.30000000000000004
    }

    [Theory]
    [InlineData("free-fall", 0.01, 5, 201)] // 1000 steps
    [InlineData("mass-spring-damper", 0.01, 10, 201)] // 2000 steps
    [InlineData("scalar-ode", 0.1, 1, 21)] // 20 steps
    public void The_default_every_keeps_the_output_near_200_rows(string scenario, double dt, int every, int rows)
    {
        var (_, data) = DemoProcess.Run(scenario, "--format", "csv").Csv();

        Assert.Equal(rows, data.Length);
        Assert.Equal(0.0, data[0][0]);
        Assert.Equal(every * dt, data[1][0]);
    }

    [Fact]
    public void The_last_step_is_printed_even_off_the_stride()
    {
        var (_, rows) = DemoProcess.Run("mass-spring-damper", "--format", "csv", "--duration", "0.07", "--every", "3").Csv();

        Assert.Equal(new[] { 0, 0.03, 0.06, 0.07 }, rows.Select(r => r[0]));
    }

    [Fact]
    public void A_duration_that_is_not_a_multiple_of_dt_ends_at_the_next_whole_step()
    {
        var (_, rows) = DemoProcess.Run("free-fall", "--format", "csv", "--duration", "0.025", "--every", "1").Csv();

        Assert.Equal(new[] { 0, 0.01, 0.02, 0.03 }, rows.Select(r => r[0]));
    }

    [Fact]
    public void Csv_is_identical_under_a_french_locale_and_the_invariant_culture()
    {
        var args = new[] { "mass-spring-damper", "--format", "csv", "--duration", "1", "--dt", "0.05" };

        var invariant = DemoProcess.RunUnder(CultureInfo.InvariantCulture, args);
        var french = DemoProcess.RunUnder(CultureInfo.GetCultureInfo("fr-FR"), args);

        Assert.Equal(0, french.ExitCode);
        Assert.Equal(invariant.Output, french.Output);
        Assert.Contains("0.05,", french.Output, StringComparison.Ordinal);
        Assert.DoesNotContain("0,05", french.Output, StringComparison.Ordinal);
    }

    [Fact]
    public void Options_are_read_in_the_invariant_culture_under_a_french_locale()
    {
        var result = DemoProcess.RunUnder(CultureInfo.GetCultureInfo("fr-FR"), "free-fall", "--format", "csv", "--dt", "0.5", "--duration", "1");

        Assert.Equal(0, result.ExitCode);
        Assert.Equal(new[] { "0", "0.5", "1" }, result.OutputLines.Skip(1).Select(l => l.Split(',')[0]));
    }

    [Fact]
    public void Numbers_are_printed_in_their_shortest_round_trip_form()
    {
        var (_, rows) = DemoProcess.Run("free-fall", "--format", "csv", "--duration", "0.5").Csv();
        var exact = new double[6];
        new FreeFallScenario().ExactState(0.5, exact);

        // The exact column, printed and read back, is the very double the core computes.
        Assert.Equal(exact[1], rows[^1][7]);
        Assert.Equal(exact[4], rows[^1][8]);
    }

    [Fact]
    public void Cloth_csv_has_one_group_of_six_columns_per_particle_and_the_mesh_extras()
    {
        var (header, rows) = DemoProcess.Run("cloth", "--format", "csv", "--resolution", "0.5", "--duration", "0.01").Csv();

        Assert.Equal(1 + (9 * 6) + 3, header.Length); // 3 x 3 particles
        Assert.Equal(new[] { "energy", "min_y", "max_speed" }, header.TakeLast(3));
        Assert.Equal(new[] { 1.0, 0, 0.5 }, rows[0].Skip(1 + (5 * 6)).Take(3)); // particle 5 = (row 1, col 2) at (col r, 0, row r)
        Assert.Equal(11, rows.Length);
    }
}
