using System.IO;
using System.Linq;
using ParticlePhysics.Demo.Scenarios;

namespace ParticlePhysics.Demo.Output;

/// <summary>
/// The convergence table in each format. csv: <c>integrator,dt,steps,error,order,expected_order</c> (order empty on
/// the first dt of each integrator, error empty when the run diverged). json:
/// <c>{ "scenario", "end_time", "levels", "parameters", "rows": [{ "integrator", "dt", "steps", "error", "order", "expected_order" }] }</c>.
/// </summary>
internal static class ConvergenceOutput
{
    public static void Write(string format, TextWriter output, ConvergenceStudy study)
    {
        switch (format)
        {
            case "csv":
                WriteCsv(output, study);
                break;
            case "json":
                WriteJson(output, study);
                break;
            default:
                WriteTable(output, study);
                break;
        }

        output.Flush();
    }

    private static void WriteTable(TextWriter output, ConvergenceStudy study)
    {
        var over = study.Setup is Running.ScalarOdeSetup ? "abs difference from the exact solution" : "max abs difference from the exact solution over positions and velocities";
        output.WriteLine($"convergence of {study.Setup.Name}: error at t = {Numbers.Brief(study.EndTime)} s ({over})");
        var table = new TextTable("integrator", ">dt (s)", ">steps", ">error", ">observed order", ">expected");
        foreach (var row in study.Rows)
        {
            table.Add(
                row.Integrator,
                Numbers.Brief(row.Plan.Dt),
                row.Plan.Steps.ToString(System.Globalization.CultureInfo.InvariantCulture),
                row.Diverged is null ? Numbers.Error(row.Error) : "diverged",
                row.Order is { } o ? o.ToString("0.00", System.Globalization.CultureInfo.InvariantCulture) : string.Empty,
                row.ExpectedOrder.ToString(System.Globalization.CultureInfo.InvariantCulture));
        }

        table.Write(output);
        output.WriteLine("observed order = log2(error(dt) / error(dt/2)); it drifts from the expected one where the error nears round-off (about 1e-13).");
    }

    private static void WriteCsv(TextWriter output, ConvergenceStudy study)
    {
        output.WriteLine("integrator,dt,steps,error,order,expected_order");
        foreach (var row in study.Rows)
        {
            var error = double.IsFinite(row.Error) ? Numbers.RoundTrip(row.Error) : string.Empty;
            var order = row.Order is { } o ? Numbers.RoundTrip(o) : string.Empty;
            output.WriteLine($"{row.Integrator},{Numbers.RoundTrip(row.Plan.Dt)},{Numbers.Json(row.Plan.Steps)},{error},{order},{Numbers.Json(row.ExpectedOrder)}");
        }
    }

    private static void WriteJson(TextWriter output, ConvergenceStudy study)
    {
        output.WriteLine("{");
        output.WriteLine($"  \"scenario\": {JsonText.String(study.Setup.Name)},");
        output.WriteLine($"  \"end_time\": {Numbers.Json(study.EndTime)},");
        output.WriteLine($"  \"levels\": {Numbers.Json(study.Levels)},");
        var parameters = study.Setup.Parameters.Select(p => $"{JsonText.String(p.Key)}: {JsonText.Value(p.Value)}");
        output.WriteLine(study.Setup.Parameters.Count == 0 ? "  \"parameters\": {}," : $"  \"parameters\": {{ {string.Join(", ", parameters)} }},");
        output.Write("  \"rows\": [");
        for (var i = 0; i < study.Rows.Count; i++)
        {
            var row = study.Rows[i];
            var order = row.Order is { } o ? Numbers.Json(o) : "null";
            output.Write(i == 0 ? "\n" : ",\n");
            output.Write($"    {{ \"integrator\": {JsonText.String(row.Integrator)}, \"dt\": {Numbers.Json(row.Plan.Dt)}, \"steps\": {Numbers.Json(row.Plan.Steps)}, ");
            output.Write($"\"error\": {Numbers.Json(row.Error)}, \"order\": {order}, \"expected_order\": {Numbers.Json(row.ExpectedOrder)}, \"diverged\": {(row.Diverged is null ? "false" : "true")} }}");
        }

        output.WriteLine(study.Rows.Count == 0 ? "]" : "\n  ]");
        output.WriteLine("}");
    }
}
