using System.Collections.Generic;
using System.Diagnostics;
using ParticlePhysics.Demo.Cli;
using ParticlePhysics.Demo.Output;
using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Demo.Scenarios;

/// <summary>
/// What the demo does with no arguments: every scenario with its defaults, under every integrator that applies,
/// and one summary table (scenario, integrator, dt, end time, final state, error against the exact solution).
/// The cloth and the drape run for <see cref="ClothSeconds"/> s rather than their defaults, to keep the whole tour to seconds.
/// </summary>
internal static class SummaryRun
{
    /// <summary>The cloth's duration in the tour.</summary>
    public const double ClothSeconds = 1;

    public static int Execute(IEnumerable<ScenarioDefinition> scenarios, DemoContext context)
    {
        var clock = Stopwatch.StartNew();
        var table = new TextTable("scenario", "integrator", ">dt (s)", ">t (s)", "final state", ">error");
        var interrupted = false;
        var footnotes = new List<string>();
        foreach (var scenario in scenarios)
        {
            if (interrupted)
            {
                break;
            }

            var setup = scenario.Configure(null);
            var duration = scenario is ClothDefinition or DrapeDefinition ? ClothSeconds : scenario.DefaultDuration;
            var steps = RunPlan.StepsFor(duration, scenario.DefaultTimeStep);
            foreach (var integrator in scenario.Integrators)
            {
                var plan = new RunPlan(integrator, scenario.DefaultTimeStep, steps, steps, 1e-8);
                RunOutcome outcome;
                try
                {
                    outcome = Runner.Run(setup, plan, null, context.Progress($"{scenario.Name} {integrator}"), cancellation: context.Cancellation);
                }
                catch (System.ArgumentException exception)
                {
                    // An integrator the catalog lists but that cannot take this system: say so in its row, run the rest.
                    table.Add(scenario.Name, integrator, Numbers.Brief(plan.Dt), string.Empty, "does not apply: " + exception.Message.Split('\n')[0], "n/a");
                    continue;
                }

                if (outcome.Interrupted)
                {
                    interrupted = true;
                    break;
                }

                var error = outcome.Diverged is { } d
                    ? $"diverged at t = {Numbers.Brief(d.Time)}"
                    : outcome.FinalError is { } e ? Numbers.Error(e) : "n/a";
                var state = Summary.FinalState(setup, outcome.FinalRow, particleLabels: true);
                if (setup.MotionEnds is { } end && end < outcome.FinalTime)
                {
                    // Zeros that mean "at rest", not "nothing happened": say when the motion ended.
                    var mark = new string('*', footnotes.Count + 1);
                    var note = $"{mark} {scenario.Name}: at rest from t = {Numbers.Brief(end)} s on (the bounces end at T = t1 (1 + e) / (1 - e)), so its final state and error are 0.";
                    if (!footnotes.Exists(f => f.EndsWith(note.Substring(mark.Length), System.StringComparison.Ordinal)))
                    {
                        footnotes.Add(note);
                    }

                    state += " " + footnotes.Find(f => f.EndsWith(note.Substring(mark.Length), System.StringComparison.Ordinal))!.Split(' ')[0];
                }

                table.Add(scenario.Name, integrator, Numbers.Brief(plan.Dt), Numbers.Brief(outcome.FinalTime), state, error);
            }
        }

        context.Output.WriteLine("ParticlePhysics demo: every scenario with its defaults (the cloth and the drape for 1 s), under every integrator that applies.");
        context.Output.WriteLine("error = max abs difference from the exact solution over positions and velocities at the final time (n/a: the cloth, the hanging chain and the drape have none; the chain's catenary_distance is its distance from its exact rest shape).");
        context.Output.WriteLine();
        table.Write(context.Output);
        foreach (var note in footnotes)
        {
            context.Output.WriteLine(note);
        }

        context.Output.WriteLine();
        if (interrupted)
        {
            context.Output.Flush();
            context.Error.WriteLine("interrupted by Ctrl-C; the table holds the runs that had finished.");
            return ExitCodes.Interrupted;
        }

        context.Output.WriteLine(string.Create(
            System.Globalization.CultureInfo.InvariantCulture,
            $"Done in {clock.Elapsed.TotalSeconds:0.0} s. Run one scenario with: dotnet run --project samples/ParticlePhysics.Demo -- SCENARIO [options]; see --help."));
        context.Output.Flush();
        return ExitCodes.Success;
    }
}
