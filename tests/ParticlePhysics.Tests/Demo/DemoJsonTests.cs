using System;
using System.Linq;
using System.Text.Json;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Tests.Demo;

/// <summary>The json format parses, and carries the run's description, its columns and its rows.</summary>
public class DemoJsonTests
{
    [Fact]
    public void Json_parses_and_has_the_columns_rows_and_summary()
    {
        var result = DemoProcess.Run("free-fall", "--format", "json", "--duration", "1", "--every", "10");

        Assert.Equal(0, result.ExitCode);
        using var document = JsonDocument.Parse(result.Output);
        var root = document.RootElement;
        Assert.Equal("free-fall", root.GetProperty("scenario").GetString());
        Assert.Equal("rk4", root.GetProperty("integrator").GetString());
        Assert.Equal(0.01, root.GetProperty("dt").GetDouble());
        Assert.Equal(0.01, root.GetProperty("parameters").GetProperty("mass").GetDouble());
        var columns = root.GetProperty("columns").EnumerateArray().Select(c => c.GetString()).ToArray();
        Assert.Equal("t", columns[0]);
        var rows = root.GetProperty("rows").EnumerateArray().ToArray();
        Assert.Equal(11, rows.Length); // steps 0, 10, ..., 100
        Assert.All(rows, r => Assert.Equal(columns.Length, r.GetArrayLength()));
        Assert.Equal(1.0, rows[^1][0].GetDouble());
        var summary = root.GetProperty("summary");
        Assert.InRange(summary.GetProperty("error").GetDouble(), 0, 1e-8);
        Assert.Equal(rows[^1][Array.IndexOf(columns, "y0")].GetDouble(), summary.GetProperty("final").GetProperty("y0").GetDouble());
        Assert.Equal(JsonValueKind.Null, root.GetProperty("diverged").ValueKind);
    }

    [Fact]
    public void Json_without_an_exact_solution_has_a_null_error()
    {
        var result = DemoProcess.Run("cloth", "--format", "json", "--resolution", "0.5", "--duration", "0.01", "--pin", "edge");

        using var document = JsonDocument.Parse(result.Output);
        Assert.Equal(JsonValueKind.Null, document.RootElement.GetProperty("summary").GetProperty("error").ValueKind);
        Assert.Equal("edge", document.RootElement.GetProperty("parameters").GetProperty("pin").GetString());
    }

    [Fact]
    public void Json_parameters_hold_the_values_as_run_including_derived_starting_heights()
    {
        var result = DemoProcess.Run("two-mass-chain", "--format", "json", "--duration", "0.01", "--rest-length2", "0.5", "--k2", "20");

        using var document = JsonDocument.Parse(result.Output);
        var parameters = document.RootElement.GetProperty("parameters");
        Assert.Equal(20.0, parameters.GetProperty("k2").GetDouble());
        Assert.Equal(-1.0, parameters.GetProperty("y1").GetDouble()); // -L1
        Assert.Equal(-1.5, parameters.GetProperty("y2").GetDouble()); // -L1 - L2
    }

    [Fact]
    public void Convergence_json_parses_and_has_one_row_per_integrator_and_level()
    {
        var result = DemoProcess.Run("convergence", "scalar-ode", "--format", "json", "--levels", "3");

        using var document = JsonDocument.Parse(result.Output);
        var rows = document.RootElement.GetProperty("rows").EnumerateArray().ToArray();
        // Every fixed-step integrator that takes a plain ODE (rk45 is adaptive; two need positions and velocities).
        var integrators = IntegratorCatalog.Names.Count(n => !IntegratorCatalog.NeedsSecondOrderSystem(n) && IntegratorCatalog.Create(n) is not DormandPrince45);
        Assert.Equal(integrators * 3, rows.Length);
        Assert.Contains(rows, r => r.GetProperty("integrator").GetString() == "explicit-euler");
        Assert.DoesNotContain(rows, r => r.GetProperty("integrator").GetString() == "velocity-verlet");
        Assert.Equal(JsonValueKind.Null, rows[0].GetProperty("order").ValueKind);
        Assert.Equal(4.0, rows[^1].GetProperty("order").GetDouble(), 0.2);
    }
}
