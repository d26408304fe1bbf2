using System.CommandLine;
using System.Linq;
using ParticlePhysics.Demo.Cli;
using ParticlePhysics.Demo.Output;
using ParticlePhysics.Demo.Running;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenes;

namespace ParticlePhysics.Demo.Scenarios;

/// <summary>
/// <c>scene FILE.json [options]</c>: runs a scene file (<c>docs/scenes.md</c>), with the scenarios' options, which
/// override the file's settings when given; <c>scene --validate FILE.json</c> checks it and says what it builds. A
/// file that cannot be used is refused with one line (exit code 2) naming the file, the JSON path, the line and
/// column, the value and what is allowed.
/// </summary>
internal static class SceneCommand
{
    /// <summary>The name of the command.</summary>
    public const string Name = "scene";

    public static Command Create(DemoContext context)
    {
        var file = new Argument<string>("FILE.json") { Description = "The scene file (see docs/scenes.md and samples/scenes/)" };
        var validate = new Option<bool>("--validate") { Description = "Check the file and print what it builds (particles, constraints by kind, colliders), without running it" };
        var integrator = new Option<string?>("--integrator")
        {
            Description = $"The integrator [default: the file's, else xpbd]: {string.Join(", ", IntegratorCatalog.Names)}",
            HelpName = "name",
        };
        integrator.Validators.Add(result =>
        {
            var name = result.GetValueOrDefault<string?>();
            if (name is not null && !IntegratorCatalog.Names.Contains(name))
            {
                result.AddError($"unknown integrator '{name}'{Suggestions.DidYouMean(name, IntegratorCatalog.Names)}; expected one of: {string.Join(", ", IntegratorCatalog.Names)}.");
            }
        });
        var dt = Options.OptionalNumber("--dt", "Time step [default: the file's, else 1/60] (for rk45: the output interval)", "s", NumberRule.Positive);
        var duration = Options.OptionalNumber("--duration", "Simulated time [default: the file's, else 5]", "s", NumberRule.Positive);
        var every = Options.Count("--every", "Print every N-th step (and always step 0 and the last) [default: near 200 rows]", 1);
        var format = Options.Choice("--format", "Output: a summary table for people, csv or json for programs", OutputFormat.Default, OutputFormat.Names.ToArray());
        var plot = CommonOptions.PlotOption("A chart of the run: the heights of the first particles against time");
        var animate = new Option<string?>("--animate")
        {
            Description = "A self-contained HTML page that replays the run in 3D in a browser",
            HelpName = "FILE.html",
        };
        var tolerance = Options.OptionalNumber("--tolerance", "rk45's error bound per internal step [default: the file's, else 1e-8]", string.Empty, NumberRule.Tolerance);
        var substeps = Options.Count("--substeps", "xpbd's substeps per step [default: the file's, else 10]", 1, null, Xpbd.MaxSubsteps);
        var profile = CommonOptions.ProfileOption();

        var command = new Command(Name, "Run a scene file: particles, springs, rods, cables, loads and colliders described in JSON (docs/scenes.md); --validate only checks it.");
        command.Add(file);
        foreach (var option in new Option[] { validate, integrator, dt, duration, every, format, plot, animate, tolerance, substeps, profile })
        {
            command.Add(option);
        }

        command.SetAction(parse =>
        {
            var path = parse.GetValue(file)!;
            var scene = Scene.Load(path);
            if (parse.GetValue(validate))
            {
                var description = scene.Describe();
                context.Output.WriteLine($"{path}: valid");
                context.Output.WriteLine(description);
                context.Output.Flush();
                return ExitCodes.Success;
            }

            if (scene.ParticleCount == 0)
            {
                throw new UsageException($"{path}: the scene has no particles to run; add an object such as {{\"type\": \"particles\", \"positions\": [[0, 1, 0]]}}.");
            }

            var settings = scene.Settings;
            var step = parse.GetValue(dt) ?? settings.TimeStep;
            var steps = RunPlan.StepsFor(parse.GetValue(duration) ?? settings.Duration, step);
            var plan = new RunPlan(
                parse.GetValue(integrator) ?? settings.Integrator,
                step,
                steps,
                parse.GetValue(every) ?? RunPlan.DefaultEvery(steps),
                parse.GetValue(tolerance) ?? settings.Tolerance,
                parse.GetValue(substeps) ?? settings.Substeps,
                parse.GetValue(profile));
            var setup = new SceneSetup(path, scene);
            return RunAction.Execute(setup, plan, parse.GetValue(format)!, parse.GetValue(plot), parse.GetValue(animate), context);
        });
        return command;
    }
}
