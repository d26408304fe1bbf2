using System.IO;
using System.Linq;
using ParticlePhysics.Demo.Running;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Demo.Output;

/// <summary>
/// The <c>table</c> format, for people: a title line, the scenario's few table columns aligned with five significant
/// digits (streamed, so a long run shows rows as they come), and a summary line with the final state and the error
/// against the exact solution where there is one.
/// </summary>
internal sealed class TableRunWriter : IRunWriter
{
    private const int MinimumWidth = 12;
    private readonly TextWriter _output;
    private ScenarioSetup? _setup;
    private int[] _indices = System.Array.Empty<int>();
    private int[] _widths = System.Array.Empty<int>();

    public TableRunWriter(TextWriter output)
    {
        _output = output;
    }

    public void Begin(ScenarioSetup setup, RunPlan plan)
    {
        _setup = setup;
        var columns = setup.Columns.ToList();
        _indices = setup.TableColumns.Select(c => columns.IndexOf(c)).ToArray();
        _widths = setup.TableColumns.Select(c => System.Math.Max(MinimumWidth, c.Length)).ToArray();
        _output.WriteLine(
            $"{setup.Name}: {plan.Integrator}{(IntegratorCatalog.IsPositionBased(plan.Integrator) ? $" ({plan.Substeps} substeps)" : string.Empty)}, dt = {Numbers.Brief(plan.Dt)} s, {plan.Steps} steps to t = {Numbers.Brief(plan.EndTime)} s, {(plan.Every == 1 ? "a row every step" : $"a row every {plan.Every} steps")}");
        _output.WriteLine(string.Join(" ", setup.TableColumns.Select((c, i) => c.PadLeft(_widths[i]))));
    }

    public void WriteRow(double[] row) =>
        _output.WriteLine(string.Join(" ", _indices.Select((c, i) => Numbers.Brief(row[c]).PadLeft(_widths[i]))));

    public void End(RunOutcome outcome)
    {
        _output.WriteLine(Summary.Describe(_setup!, outcome));
        foreach (var line in _setup!.SummaryDetails)
        {
            _output.WriteLine(line);
        }

        _output.Flush();
    }
}
