using System.CommandLine;
using ParticlePhysics.Demo.Cli;
using ParticlePhysics.Demo.Output;
using ParticlePhysics.Demo.Plotting;
using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Demo.Scenarios;

/// <summary>
/// The command that runs one scenario (<c>free-fall</c>, <c>cloth</c>, ...): its physical options and the common
/// ones; the action streams rows to the chosen writer, draws the plot, and reports a divergence (exit code 3).
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
            PlotFile.CheckWritable(plotPath);
        }

        var plot = plotPath is null ? null : RunPlots.For(setup, plan);
        var writer = OutputFormat.CreateRunWriter(parse.GetValue(options.Format)!, context.Output);

        writer.Begin(setup, plan);
        var outcome = Runner.Run(
            setup,
            plan,
            writer.WriteRow,
            context.Progress(scenario.Name),
            plot);
        writer.End(outcome);
        if (plot is not null)
        {
            PlotFile.Write(plotPath!, plot.ToSvg(outcome));
        }

        if (outcome.Diverged is { } divergence)
        {
            context.Error.WriteLine(DivergenceMessage.For(divergence, plan));
            return ExitCodes.Diverged;
        }

        return ExitCodes.Success;
    }
}
