using System.Collections.Generic;
using System.Linq;
using ParticlePhysics.Demo.Animation;
using ParticlePhysics.Demo.Cli;
using ParticlePhysics.Demo.Output;
using ParticlePhysics.Demo.Plotting;
using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Demo.Scenarios;

/// <summary>
/// Runs one configured setup (a scenario's or a scene's): checks the plot and page paths before anything is printed,
/// streams rows to the chosen writer (flushed row by row when stdout is a terminal), draws the plot, writes the replay
/// page, and reports a divergence (exit code 3) or an interruption by Ctrl-C (130).
/// </summary>
internal static class RunAction
{
    public static int Execute(ScenarioSetup setup, RunPlan plan, string format, string? plotPath, string? animatePath, DemoContext context)
    {
        if (plotPath is not null)
        {
            OutputFile.CheckWritable("--plot", plotPath);
            OutputFile.CheckExtension("--plot", plotPath, "SVG", ".svg");
        }

        var particles = setup as IParticleRun;
        if (animatePath is not null)
        {
            if (particles is null)
            {
                throw new UsageException($"--animate replays particles, and {setup.Name} is a plain ODE with none; use --plot FILE.svg for its curve.");
            }

            OutputFile.CheckWritable("--animate", animatePath);
            OutputFile.CheckExtension("--animate", animatePath, "an HTML page", ".html", ".htm");
        }

        // Before anything is printed: a long or large run says what it will cost, and the world is built (a scenario
        // the core refuses is a bad command line, exit code 2, not a failure halfway through the output).
        if (RunCost.For(setup, plan) is { IsWorthSaying: true } cost)
        {
            context.Error.WriteLine(cost.Note(setup.Name, plan));
        }

        setup.Prepare();
        var timings = plan.Profile ? new StageTimings() : null;
        var plot = plotPath is null ? null : RunPlots.For(setup, plan);
        var recorder = animatePath is null ? null : new ReplayRecorder(setup, particles!.ParticleCount, plan, timings);
        var observers = new List<IRunObserver>();
        if (plot is not null)
        {
            observers.Add(plot);
        }

        if (recorder is not null)
        {
            observers.Add(recorder);
        }

        var writer = OutputFormat.CreateRunWriter(format, context.Output);
        var progress = context.Progress(setup.Name);
        writer.Begin(setup, plan);
        void WriteRow(double[] row)
        {
            if (!context.OutputIsTerminal)
            {
                writer.WriteRow(row);
                return;
            }

            // On a terminal each row shows as it is computed, above the progress line (which shares the screen).
            if (progress is null)
            {
                writer.WriteRow(row);
                context.Output.Flush();
                return;
            }

            progress.WriteAbove(() =>
            {
                writer.WriteRow(row);
                context.Output.Flush();
            });
        }

        var outcome = Runner.Run(setup, plan, WriteRow, progress, observers, context.Cancellation, timings);
        writer.End(outcome);
        if (timings is not null)
        {
            ProfileReport.Write(context.Error, timings);
        }

        if (plot is not null)
        {
            OutputFile.Write("--plot", plotPath!, plot.ToSvg(outcome));
        }

        if (recorder is not null)
        {
            var scene = SceneReader.Read(particles!.BuildWorld(), particles.SurfaceSide);
            OutputFile.Write("--animate", animatePath!, stream => ReplayPage.Write(
                stream,
                scene,
                recorder,
                $"{setup.Name}: {plan.Integrator}, dt = {Numbers.Brief(plan.Dt)} s, {plan.Steps} steps to t = {Numbers.Brief(plan.EndTime)} s",
                particles.Subtitle ?? Parameters(setup),
                Summary.Describe(setup, outcome)));
        }

        if (outcome.Diverged is { } divergence)
        {
            context.Error.WriteLine(DivergenceMessage.For(divergence, plan));
            return ExitCodes.Diverged;
        }

        if (outcome.Interrupted)
        {
            context.Error.WriteLine($"interrupted by Ctrl-C at t = {Numbers.Brief(outcome.FinalTime)} s (step {outcome.FinalStep} of {plan.Steps}); the rows printed so far were kept.");
            return ExitCodes.Interrupted;
        }

        return ExitCodes.Success;
    }

    private static string Parameters(ScenarioSetup setup) =>
        setup.Parameters.Count == 0
            ? "no parameters"
            : string.Join(", ", setup.Parameters.Select(p => $"{p.Key} = {(p.Value is double d ? Numbers.Brief(d) : p.Value)}"));
}
