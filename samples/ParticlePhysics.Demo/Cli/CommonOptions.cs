using System.Collections.Generic;
using System.CommandLine;
using System.Linq;
using ParticlePhysics.Demo.Output;
using ParticlePhysics.Demo.Scenarios;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Demo.Cli;

/// <summary>The options every scenario command takes: integrator, time step, duration, output.</summary>
internal sealed class CommonOptions
{
    public CommonOptions(ScenarioDefinition scenario)
    {
        Integrator = IntegratorOption(scenario, IntegratorCatalog.DefaultName, "The integrator");
        Dt = Options.Number("--dt", "Time step (for rk45: the output interval)", "s", scenario.DefaultTimeStep, NumberRule.Positive);
        Duration = Options.Number("--duration", "Simulated time; the last step ends at or just past it", "s", scenario.DefaultDuration, NumberRule.Positive);
        Every = Options.Count("--every", "Print every N-th step (and always step 0 and the last) [default: near 200 rows]", 1);
        Format = Options.Choice("--format", "Output: aligned table for people, csv or json for programs", OutputFormat.Default, OutputFormat.Names.ToArray());
        Plot = PlotOption("A chart of the run: the trajectory against the exact solution, or snapshots of the cloth mesh");
        Animate = new Option<string?>("--animate")
        {
            Description = "A self-contained HTML page that replays the run in 3D in a browser (particles, springs, pins; play, pause, time slider, orbiting camera)",
            HelpName = "FILE.html",
        };
        Tolerance = Options.Number("--tolerance", "rk45's error bound per internal step (relative to 1 + |y|)", string.Empty, 1e-8, NumberRule.Tolerance);
        Substeps = scenario.IsPlainOde ? null : SubstepsOption();
        Profile = scenario.IsPlainOde ? null : ProfileOption();
    }

    public Option<string> Integrator { get; }

    public Option<double> Dt { get; }

    public Option<double> Duration { get; }

    public Option<int?> Every { get; }

    public Option<string> Format { get; }

    public Option<string?> Plot { get; }

    public Option<string?> Animate { get; }

    public Option<double> Tolerance { get; }

    /// <summary><c>--substeps</c>, for particle scenarios only (xpbd needs positions and velocities).</summary>
    public Option<int?>? Substeps { get; }

    /// <summary><c>--profile</c>, for particle scenarios only (a plain ODE has no world whose stages to time).</summary>
    public Option<bool>? Profile { get; }

    public IEnumerable<Option> All =>
        Substeps is null || Profile is null
            ? new Option[] { Integrator, Dt, Duration, Every, Format, Plot, Animate, Tolerance }
            : new Option[] { Integrator, Dt, Duration, Every, Format, Plot, Animate, Tolerance, Substeps, Profile };

    /// <summary><c>--profile</c>: time each step's stages and print them after the run.</summary>
    public static Option<bool> ProfileOption() => new("--profile")
    {
        Description = "Time each step's stages (integration, forces, constraints, contacts) and print them after the run, on standard error; a replay shows them per frame",
    };

    /// <summary><c>--substeps N</c>: xpbd's substeps per step, a whole number from 1 to 1000 (default 10).</summary>
    public static Option<int?> SubstepsOption() =>
        Options.Count("--substeps", "xpbd's substeps per step, one projection pass each", 1, Xpbd.DefaultSubsteps, Xpbd.MaxSubsteps);

    /// <summary>The parsed <c>--substeps</c>, or the default.</summary>
    public int SubstepsValue(ParseResult parse) =>
        Substeps is null ? Xpbd.DefaultSubsteps : parse.GetValue(Substeps) ?? Xpbd.DefaultSubsteps;

    /// <summary>The parsed <c>--profile</c> (false where the option does not exist).</summary>
    public bool ProfileValue(ParseResult parse) => Profile is not null && parse.GetValue(Profile);

    /// <summary><c>--plot FILE.svg</c>.</summary>
    public static Option<string?> PlotOption(string description) => new("--plot") { Description = description, HelpName = "FILE.svg" };

    /// <summary>
    /// <c>--integrator</c>: one of <see cref="IntegratorCatalog.Names"/> that applies to <paramref name="scenario"/>;
    /// a catalog name that does not apply is refused with the reason.
    /// </summary>
    public static Option<string> IntegratorOption(ScenarioDefinition scenario, string? defaultName, string description)
    {
        var applicable = scenario.Integrators;
        var option = new Option<string>("--integrator")
        {
            Description = $"{description}: {string.Join(", ", applicable)}",
            HelpName = "name",
        };
        if (defaultName is not null)
        {
            option.DefaultValueFactory = _ => defaultName;
        }

        option.Validators.Add(result =>
        {
            var name = result.GetValueOrDefault<string>();
            if (applicable.Contains(name))
            {
                return;
            }

            result.AddError(IntegratorCatalog.Names.Contains(name)
                ? $"--integrator {name} does not apply to {scenario.Name}: it needs a position/velocity system and {scenario.Name} is a plain first-order ODE; use one of: {string.Join(", ", applicable)}."
                : $"unknown integrator '{name}'{Suggestions.DidYouMean(name, applicable)}; expected one of: {string.Join(", ", applicable)}.");
        });
        return option;
    }
}
