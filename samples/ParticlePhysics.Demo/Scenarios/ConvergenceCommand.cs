using System;
using System.Collections.Generic;
using System.CommandLine;
using System.Linq;
using System.Threading;
using ParticlePhysics.Demo.Cli;
using ParticlePhysics.Demo.Output;
using ParticlePhysics.Demo.Plotting;
using ParticlePhysics.Demo.Running;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Demo.Scenarios;

/// <summary>
/// <c>convergence SCENARIO</c>: runs a scenario that has an exact solution with each fixed-step integrator that
/// applies, at dt, dt/2, dt/4, ..., and reports the error at the end time (max abs over positions and velocities)
/// and the observed order log2(error(dt) / error(dt/2)). The adaptive rk45 is left out unless asked for by
/// <c>--integrator</c>: its error follows <c>--tolerance</c>, not dt, so it has no order in dt to observe.
/// </summary>
internal static class ConvergenceCommand
{
    /// <summary>The name of the command.</summary>
    public const string Name = "convergence";

    /// <summary>Why convergence does not run a scenario, by the scenario's name (for the error that names it).</summary>
    public static string? Refusal(string scenario) =>
        DemoCommandLine.Scenarios().FirstOrDefault(s => s.Name == scenario)?.ConvergenceRefusal;

    public static Command Create(IEnumerable<ScenarioDefinition> scenarios, DemoContext context)
    {
        var command = new Command(Name, "Error at the end time and observed order of each integrator as dt halves, for a scenario with an exact solution.");
        foreach (var scenario in scenarios.Where(s => s.ConvergenceRefusal is null))
        {
            command.Add(CreateFor(scenario, context));
        }

        return command;
    }

    private static Command CreateFor(ScenarioDefinition scenario, DemoContext context)
    {
        var command = new Command(scenario.Name, $"Convergence of every integrator on {scenario.Name}. {scenario.Description}");
        var integrator = CommonOptions.IntegratorOption(scenario, null, "Only this integrator [default: every fixed-step one]; one of");
        var dt = Options.Number("--dt", "The coarsest time step", "s", scenario.ConvergenceTimeStep, NumberRule.Positive);
        var duration = Options.Number("--duration", "Simulated time; the error is measured at its end", "s", scenario.ConvergenceDuration, NumberRule.Positive);
        var levels = Options.Count("--levels", "How many time steps: dt, dt/2, dt/4, ... (2 to 16)", 2, 4, 16);
        var format = Options.Choice("--format", "Output: aligned table for people, csv or json for programs", OutputFormat.Default, OutputFormat.Names.ToArray());
        var plot = CommonOptions.PlotOption("A chart of the error against dt on log-log axes");
        var tolerance = Options.Number("--tolerance", "rk45's error bound per internal step, when --integrator rk45", string.Empty, 1e-8, NumberRule.Tolerance);
        var substeps = scenario.IsPlainOde ? null : CommonOptions.SubstepsOption();
        foreach (var option in scenario.PhysicsOptions.Concat(new Option[] { integrator, dt, duration, levels, format, plot, tolerance }))
        {
            command.Add(option);
        }

        if (substeps is not null)
        {
            command.Add(substeps);
        }

        command.SetAction(parse =>
        {
            var count = parse.GetValue(levels) ?? 4;

            if (parse.GetValue(plot) is { } plotPath)
            {
                OutputFile.CheckWritable("--plot", plotPath);
                OutputFile.CheckExtension("--plot", plotPath, "SVG", ".svg");
            }

            var names = parse.GetValue(integrator) is { } one
                ? new[] { one }
                : scenario.Integrators.Where(n => !IntegratorCatalog.IsAdaptive(n)).ToArray();
            var setup = scenario.Configure(parse);
            if (setup.Exact is null)
            {
                throw new UsageException($"convergence needs an exact solution, and {scenario.Name} has one only {scenario.ExactSolutionCondition}.");
            }

            var substepCount = substeps is null ? Xpbd.DefaultSubsteps : parse.GetValue(substeps) ?? Xpbd.DefaultSubsteps;
            var study = Run(setup, names, parse.GetValue(dt), parse.GetValue(duration), count, parse.GetValue(tolerance), substepCount, context.Cancellation);
            ConvergenceOutput.Write(parse.GetValue(format)!, context.Output, study);
            if (parse.GetValue(plot) is { } path)
            {
                OutputFile.Write("--plot", path, ConvergencePlot.ToSvg(study));
            }

            if (study.Interrupted)
            {
                context.Error.WriteLine("interrupted by Ctrl-C; the rows printed were computed in full, the rest were not run.");
                return ExitCodes.Interrupted;
            }

            if (study.Rows.FirstOrDefault(r => r.Diverged is not null) is { } failed)
            {
                context.Error.WriteLine(DivergenceMessage.For(failed.Diverged!, failed.Plan));
                return ExitCodes.Diverged;
            }

            return ExitCodes.Success;
        });
        return command;
    }

    /// <summary>Runs every integrator at every level; the end time is the same for all (steps double as dt halves).</summary>
    public static ConvergenceStudy Run(
        ScenarioSetup setup,
        IReadOnlyList<string> integrators,
        double dt,
        double duration,
        int levels,
        double tolerance,
        int substeps = Xpbd.DefaultSubsteps,
        CancellationToken cancellation = default)
    {
        var steps = RunPlan.StepsFor(duration, dt);
        if ((long)steps << (levels - 1) > int.MaxValue)
        {
            throw new UsageException($"--duration / --dt gives {steps} steps, too many to halve dt {levels - 1} times.");
        }

        var rows = new List<ConvergenceRow>();
        foreach (var name in integrators)
        {
            double? previous = null;
            for (var level = 0; level < levels; level++)
            {
                var plan = new RunPlan(name, dt / (1 << level), steps << level, steps << level, tolerance, substeps);
                var outcome = Runner.Run(setup, plan, null, cancellation: cancellation);
                if (outcome.Interrupted)
                {
                    return new ConvergenceStudy(setup, steps * dt, levels, rows, Interrupted: true);
                }
                var error = outcome.Diverged is null ? outcome.FinalError ?? double.NaN : double.NaN;
                double? order = previous is > 0 && error > 0 ? Math.Log2(previous.Value / error) : null;
                rows.Add(new ConvergenceRow(name, plan, error, order, IntegratorCatalog.Create(name).Order, outcome.Diverged));
                previous = double.IsFinite(error) ? error : null;
            }
        }

        return new ConvergenceStudy(setup, steps * dt, levels, rows);
    }
}

/// <summary>One integrator at one dt: the error at the end time and the order observed against the previous dt.</summary>
internal sealed record ConvergenceRow(string Integrator, RunPlan Plan, double Error, double? Order, int ExpectedOrder, Divergence? Diverged);

/// <summary>A convergence study: the scenario, the common end time, and one row per integrator and dt.</summary>
internal sealed record ConvergenceStudy(ScenarioSetup Setup, double EndTime, int Levels, IReadOnlyList<ConvergenceRow> Rows, bool Interrupted = false);
