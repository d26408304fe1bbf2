using System.IO;
using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Demo.Output;

/// <summary>
/// csv for programs: one header row (<c>t</c>, the state columns, the extra columns), then one line per row, numbers
/// in the invariant culture and their shortest round-trip form. Nothing else: no comment, no summary.
/// </summary>
internal sealed class CsvRunWriter : IRunWriter
{
    private readonly TextWriter _output;

    public CsvRunWriter(TextWriter output)
    {
        _output = output;
    }

    public void Begin(ScenarioSetup setup, RunPlan plan) => _output.WriteLine(string.Join(',', setup.Columns));

    public void WriteRow(double[] row)
    {
        for (var i = 0; i < row.Length; i++)
        {
            if (i > 0)
            {
                _output.Write(',');
            }

            _output.Write(Numbers.RoundTrip(row[i]));
        }

        _output.WriteLine();
    }

    public void End(RunOutcome outcome) => _output.Flush();
}
