using System.IO;
using ParticlePhysics.Demo.Running;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Demo.Output;

/// <summary>
/// json for programs, streamed so that a diverged run still ends as valid JSON:
/// <code>
/// { "scenario": "free-fall", "integrator": "rk4", "dt": 0.01, "steps": 1000, "every": 5,
///   "parameters": { "mass": 0.01, ... },
///   "columns": ["t", "x0", ...],
///   "rows": [[0, 0, 300, ...], ...],
///   "summary": { "t": 10, "step": 1000, "error": 1.2e-9, "final": { "y0": ..., ... } },
///   "diverged": null }
/// </code>
/// <c>error</c> is null without an exact solution; <c>diverged</c> is <c>{ "t": ..., "message": ... }</c> when a
/// step diverged, and <c>summary</c> then describes the last good state; a run stopped by Ctrl-C adds
/// <c>"interrupted": true</c> after it. Non-finite numbers are written as null.
/// </summary>
internal sealed class JsonRunWriter : IRunWriter
{
    private readonly TextWriter _output;
    private ScenarioSetup? _setup;
    private bool _firstRow = true;

    public JsonRunWriter(TextWriter output)
    {
        _output = output;
    }

    public void Begin(ScenarioSetup setup, RunPlan plan)
    {
        _setup = setup;
        var o = _output;
        o.WriteLine("{");
        o.WriteLine($"  {JsonText.String(setup.JsonNameKey)}: {JsonText.String(setup.Name)},");
        o.WriteLine($"  \"integrator\": {JsonText.String(plan.Integrator)},");
        o.WriteLine($"  \"dt\": {Numbers.Json(plan.Dt)},");
        o.WriteLine($"  \"steps\": {Numbers.Json(plan.Steps)},");
        o.WriteLine($"  \"every\": {Numbers.Json(plan.Every)},");
        if (plan.Integrator == "rk45")
        {
            o.WriteLine($"  \"tolerance\": {Numbers.Json(plan.Tolerance)},");
        }

        if (IntegratorCatalog.IsPositionBased(plan.Integrator))
        {
            o.WriteLine($"  \"substeps\": {Numbers.Json(plan.Substeps)},");
        }

        if (setup.HasParameters)
        {
            o.Write("  \"parameters\": {");
            for (var i = 0; i < setup.Parameters.Count; i++)
            {
                var (name, value) = (setup.Parameters[i].Key, setup.Parameters[i].Value);
                o.Write($"{(i == 0 ? " " : ", ")}{JsonText.String(name)}: {JsonText.Value(value)}");
            }

            o.WriteLine(setup.Parameters.Count == 0 ? "}," : " },");
        }

        o.Write("  \"columns\": [");
        for (var i = 0; i < setup.Columns.Count; i++)
        {
            o.Write($"{(i == 0 ? string.Empty : ", ")}{JsonText.String(setup.Columns[i])}");
        }

        o.WriteLine("],");
        o.Write("  \"rows\": [");
    }

    public void WriteRow(double[] row)
    {
        _output.Write(_firstRow ? "\n    [" : ",\n    [");
        _firstRow = false;
        for (var i = 0; i < row.Length; i++)
        {
            if (i > 0)
            {
                _output.Write(", ");
            }

            _output.Write(Numbers.Json(row[i]));
        }

        _output.Write(']');
    }

    public void End(RunOutcome outcome)
    {
        var o = _output;
        var columns = _setup!.Columns;
        o.WriteLine(_firstRow ? "]," : "\n  ],");
        o.Write($"  \"summary\": {{ \"t\": {Numbers.Json(outcome.FinalTime)}, \"step\": {Numbers.Json(outcome.FinalStep)}, ");
        o.Write($"\"error\": {(outcome.FinalError is { } e ? Numbers.Json(e) : "null")}, \"final\": ");
        if (_setup.FinalJson(outcome) is { } final)
        {
            o.Write(final);
        }
        else
        {
            o.Write('{');
            var first = true;
            foreach (var name in _setup.SummaryColumns)
            {
                o.Write($"{(first ? " " : ", ")}{JsonText.String(name)}: {Numbers.Json(outcome.FinalRow[IndexOf(columns, name)])}");
                first = false;
            }

            o.Write(" }");
        }

        o.WriteLine(" },");
        if (outcome.Diverged is { } d)
        {
            o.Write($"  \"diverged\": {{ \"t\": {Numbers.Json(d.Time)}, \"message\": {JsonText.String(d.Exception.Message)} }}");
        }
        else
        {
            o.Write("  \"diverged\": null");
        }

        // Ctrl-C: the document still closes, and says so.
        o.WriteLine(outcome.Interrupted ? ",\n  \"interrupted\": true" : string.Empty);

        o.WriteLine("}");
        o.Flush();
    }

    private static int IndexOf(System.Collections.Generic.IReadOnlyList<string> columns, string name)
    {
        for (var i = 0; i < columns.Count; i++)
        {
            if (columns[i] == name)
            {
                return i;
            }
        }

        return -1;
    }
}
