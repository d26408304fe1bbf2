using System.CommandLine;
using ParticlePhysics.Demo.Cli;
using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Demo.Scenarios;

/// <summary>
/// The command that runs one scenario (<c>free-fall</c>, <c>cloth</c>, ...): its physical options and the common
/// ones; <see cref="RunAction"/> runs it.
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
            options.SubstepsValue(parse),
            options.ProfileValue(parse));
        return RunAction.Execute(setup, plan, parse.GetValue(options.Format)!, parse.GetValue(options.Plot), parse.GetValue(options.Animate), context);
    }
}
