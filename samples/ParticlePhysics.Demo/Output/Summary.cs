using System.Linq;
using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Demo.Output;

/// <summary>One-line descriptions of a run's final state, for the table format and the default run's summary.</summary>
internal static class Summary
{
    /// <summary>"final state at t = 10 s: y0 = 12.3, vy0 = -0.98; error against the exact solution: 1.23E-09".</summary>
    public static string Describe(ScenarioSetup setup, RunOutcome outcome)
    {
        var head = outcome.Diverged is not null
            ? $"diverged at t = {Numbers.Brief(outcome.Diverged.Time)} s; last good state at t = {Numbers.Brief(outcome.FinalTime)} s: "
            : outcome.Interrupted
                ? $"interrupted (Ctrl-C) at t = {Numbers.Brief(outcome.FinalTime)} s; state there: "
                : $"final state at t = {Numbers.Brief(outcome.FinalTime)} s: ";
        var over = setup is ScalarOdeSetup ? string.Empty : " (max abs over positions and velocities)";
        var error = outcome.FinalError is { } e
            ? $"; error against the exact solution{over}: {Numbers.Error(e)}"
            : string.Empty;
        return head + FinalState(setup, outcome.FinalRow) + error;
    }

    /// <summary>
    /// "y0 = 12.3, vy0 = -0.98": the scenario's summary columns, named as the run's table columns are; with
    /// <paramref name="particleLabels"/> (the tour, which shows no columns) a particle's values by its index in brackets,
    /// "y[0] = 12.3", since y0 alone reads as the starting height that --y0 names.
    /// </summary>
    public static string FinalState(ScenarioSetup setup, double[] row, bool particleLabels = false)
    {
        var columns = setup.Columns.ToList();
        return string.Join(", ", setup.SummaryColumns.Select(c => $"{(particleLabels ? Label(c) : c)} = {Numbers.Brief(row[columns.IndexOf(c)])}"));
    }

    /// <summary>A column's name for people: <c>y0</c> becomes <c>y[0]</c>, <c>vx12</c> <c>vx[12]</c>; others stay.</summary>
    public static string Label(string column)
    {
        var match = System.Text.RegularExpressions.Regex.Match(column, "^(v?[xyz])([0-9]+)$");
        return match.Success ? $"{match.Groups[1].Value}[{match.Groups[2].Value}]" : column;
    }
}
