using System.Collections.Generic;
using System.CommandLine;
using System.Linq;
using ParticlePhysics.Demo.Animation;
using ParticlePhysics.Demo.Cli;
using ParticlePhysics.Demo.Output;
using ParticlePhysics.Demo.Plotting;
using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Demo.Scenarios;

/// <summary>
/// The command that runs one scenario (<c>free-fall</c>, <c>cloth</c>, ...): its physical options and the common
/// ones; the action streams rows to the chosen writer (flushed row by row when stdout is a terminal), draws the
/// plot, writes the replay page, and reports a divergence (exit code 3) or an interruption by Ctrl-C (130).
/// </summary>
internal static class ScenarioCommand
{
    public static Command Create(ScenarioDefinition scenario, DemoContext context)
    {
        var common = new CommonOptions(scenario);
        var command = new Command(scenario.Name, scenario.Description);
        foreach (var option in scenario.PhysicsOptions)
        {
            command.Add(option);
        }

        foreach (var option in common.All)
        {
            command.Add(option);
        }

        command.SetAction(parse => Execute(parse, scenario, common, context));
        return command;
    }

    private static int Execute(ParseResult parse, ScenarioDefinition scenario, CommonOptions options, DemoContext context)
    {
        var setup = scenario.Configure(parse);
        var dt = parse.GetValue(options.Dt);
        var steps = RunPlan.StepsFor(parse.GetValue(options.Duration), dt);
        var plan = new RunPlan(
            parse.GetValue(options.Integrator)!,
            dt,
            steps,
            parse.GetValue(options.Every) ?? RunPlan.DefaultEvery(steps),
            parse.GetValue(options.Tolerance),
            options.SubstepsValue(parse));
        var plotPath = parse.GetValue(options.Plot);
        if (plotPath is not null)
        {
            OutputFile.CheckWritable("--plot", plotPath);
        }

        var animatePath = parse.GetValue(options.Animate);
        var particles = setup as ParticleSetup;
        if (animatePath is not null)
        {
            if (particles is null)
            {
                throw new UsageException($"--animate replays particles, and {scenario.Name} is a plain ODE with none; use --plot FILE.svg for its curve.");
            }

            OutputFile.CheckWritable("--animate", animatePath);
        }

        // Before anything is printed: a long or large run says what it will cost, and the world is built (a scenario
        // the core refuses is a bad command line, exit code 2, not a failure halfway through the output).
        if (RunCost.For(setup, plan) is { IsWorthSaying: true } cost)
        {
            context.Error.WriteLine(cost.Note(scenario.Name, plan));
        }

        setup.Prepare();
        var plot = plotPath is null ? null : RunPlots.For(setup, plan);
        var recorder = animatePath is null ? null : new ReplayRecorder(particles!, plan);
        var observers = new List<IRunObserver>();
        if (plot is not null)
        {
            observers.Add(plot);
        }

        if (recorder is not null)
        {
            observers.Add(recorder);
        }

        var writer = OutputFormat.CreateRunWriter(parse.GetValue(options.Format)!, context.Output);
        var progress = context.Progress(scenario.Name);
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

        var outcome = Runner.Run(setup, plan, WriteRow, progress, observers, context.Cancellation);
        writer.End(outcome);
        if (plot is not null)
        {
            OutputFile.Write("--plot", plotPath!, plot.ToSvg(outcome));
        }

        if (recorder is not null)
        {
            var cloth = setup as ClothSetup;
            var scene = SceneReader.Read(particles!.BuildWorld(), cloth?.ParticlesPerSide ?? 0);
            OutputFile.Write("--animate", animatePath!, stream => ReplayPage.Write(
                stream,
                scene,
                recorder,
                $"{setup.Name}: {plan.Integrator}, dt = {Numbers.Brief(plan.Dt)} s, {plan.Steps} steps to t = {Numbers.Brief(plan.EndTime)} s",
                Parameters(setup),
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
