using System;
using System.Collections.Generic;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Demo.Running;

/// <summary>
/// A scenario with every parameter fixed: it builds fresh simulations, knows its exact solution (if any), and lays
/// out one output row (column 0 is always <c>t</c>).
/// </summary>
internal abstract class ScenarioSetup
{
    private ISimulation? _prepared;

    protected ScenarioSetup(string name, IExactSolution? exact)
    {
        Name = name;
        Exact = exact;
    }

    /// <summary>The scenario's command name, such as <c>free-fall</c>.</summary>
    public string Name { get; }

    /// <summary>The exact solution, or null when there is none (cloth).</summary>
    public IExactSolution? Exact { get; }

    /// <summary>The parameters as given or defaulted, for the JSON header: a double or a string each.</summary>
    public IReadOnlyList<KeyValuePair<string, object>> Parameters { get; set; } = Array.Empty<KeyValuePair<string, object>>();

    /// <summary>Every column of a row, for csv and json: <c>t</c>, the state, then the extra columns.</summary>
    public abstract IReadOnlyList<string> Columns { get; }

    /// <summary>The few columns the <c>table</c> format shows (names from <see cref="Columns"/>, <c>t</c> first).</summary>
    public abstract IReadOnlyList<string> TableColumns { get; }

    /// <summary>The columns that describe the final state in summaries (a subset of <see cref="TableColumns"/>).</summary>
    public abstract IReadOnlyList<string> SummaryColumns { get; }

    /// <summary>The curves of a trajectory plot: a computed column and its exact counterpart (or null).</summary>
    public abstract IReadOnlyList<(string Column, string? Exact)> PlotSeries { get; }

    /// <summary>The vertical axis of a trajectory plot.</summary>
    public virtual string PlotAxisLabel => "height y (m)";

    /// <summary>
    /// Lines the table format prints after its summary line, about the last run of <see cref="CreateSimulation"/> (the
    /// bouncing ball's apexes against the exact ones); none by default.
    /// </summary>
    public virtual IReadOnlyList<string> SummaryDetails => Array.Empty<string>();

    /// <summary>When the motion ends (the bouncing ball comes to rest), in s, or null: a summary says so where it shows a still state.</summary>
    public virtual double? MotionEnds => null;

    /// <summary>The json header's name for what runs: <c>scenario</c>, or <c>scene</c> for a scene file.</summary>
    public virtual string JsonNameKey => "scenario";

    /// <summary>True when the json header lists <see cref="Parameters"/> (a scene's are in its file).</summary>
    public virtual bool HasParameters => true;

    /// <summary>The json summary's <c>final</c> object, or null for the <see cref="SummaryColumns"/> of the final row.</summary>
    public virtual string? FinalJson(RunOutcome outcome) => null;

    /// <summary>The exact value of <paramref name="exactColumn"/> (one of the <c>..._exact</c> columns) at any time, for smooth plots.</summary>
    public double ExactValue(string exactColumn, double time)
    {
        var row = new double[Columns.Count];
        FillExact(time, row);
        return row[IndexOf(exactColumn)];
    }

    /// <summary>The index of a column.</summary>
    public int IndexOf(string column)
    {
        for (var i = 0; i < Columns.Count; i++)
        {
            if (Columns[i] == column)
            {
                return i;
            }
        }

        throw new ArgumentException($"no column '{column}' in {Name}.", nameof(column));
    }

    /// <summary>Writes the exact columns of a row at <paramref name="time"/> (the other columns are left alone).</summary>
    protected abstract void FillExact(double time, Span<double> row);

    /// <summary>Builds a fresh simulation at t = 0.</summary>
    public abstract ISimulation CreateSimulation();

    /// <summary>
    /// Builds the simulation that the next <see cref="TakeSimulation"/> returns, now: a scenario that cannot be built
    /// (a cloth whose particles' mass is too small, a size beyond the world's limit) fails before anything is printed.
    /// </summary>
    /// <exception cref="UsageException">The core refused to build it.</exception>
    public void Prepare()
    {
        try
        {
            _prepared ??= CreateSimulation();
        }
        catch (InvalidOperationException exception)
        {
            throw new UsageException(exception.Message, exception);
        }
    }

    /// <summary>The simulation <see cref="Prepare"/> built, or a fresh one; each simulation is taken once.</summary>
    public ISimulation TakeSimulation()
    {
        var simulation = _prepared ?? CreateSimulation();
        _prepared = null;
        return simulation;
    }

    /// <summary>Writes the row of <paramref name="simulation"/> at time <paramref name="time"/> into <paramref name="row"/>.</summary>
    public abstract void FillRow(ISimulation simulation, double time, Span<double> row);

    /// <summary>The error against the exact solution at <paramref name="time"/>: max abs over the state vector, or null.</summary>
    public double? ErrorAt(ISimulation simulation, double time)
    {
        if (Exact is null)
        {
            return null;
        }

        var state = simulation.State;
        Span<double> exact = state.Length <= 64 ? stackalloc double[state.Length] : new double[state.Length];
        Exact.ExactState(time, exact);
        return MaxAbsDifference(state, exact);
    }

    /// <summary>max_i |a_i - b_i|; NaN when any difference is NaN.</summary>
    public static double MaxAbsDifference(ReadOnlySpan<double> a, ReadOnlySpan<double> b)
    {
        var max = 0.0;
        for (var i = 0; i < a.Length; i++)
        {
            var d = Math.Abs(a[i] - b[i]);
            if (double.IsNaN(d))
            {
                return double.NaN;
            }

            max = Math.Max(max, d);
        }

        return max;
    }
}
