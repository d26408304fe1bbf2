using System.Collections.Generic;
using System.CommandLine;
using System.Linq;
using ParticlePhysics.Demo.Running;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Demo.Scenarios;

/// <summary>
/// One scenario of the contract as the command line sees it: its name, its physical options (each with the core
/// builder's default, so defaults live in one place), and how to turn parsed values into a <see cref="ScenarioSetup"/>.
/// Each instance owns its option objects, so build one per command.
/// </summary>
internal abstract class ScenarioDefinition
{
    /// <summary>The command name, such as <c>free-fall</c>.</summary>
    public abstract string Name { get; }

    /// <summary>One line for the help.</summary>
    public abstract string Description { get; }

    /// <summary>The contract's default <c>--dt</c>, in s.</summary>
    public abstract double DefaultTimeStep { get; }

    /// <summary>The contract's default <c>--duration</c>, in s.</summary>
    public abstract double DefaultDuration { get; }

    /// <summary>True when the scenario has an exact solution (every one but the cloth).</summary>
    public virtual bool HasExactSolution => true;

    /// <summary>When the exact solution holds, for the error a convergence study gives without one ("without drag (--drag 0)").</summary>
    public virtual string ExactSolutionCondition => "with other options";

    /// <summary>
    /// Why <c>convergence</c> does not run this scenario, or null when it does (it has an exact solution whose error
    /// shrinks with dt at each integrator's order).
    /// </summary>
    public virtual string? ConvergenceRefusal => HasExactSolution ? null : "it has no exact solution to measure the error against";

    /// <summary>True for a plain first-order ODE, which refuses the integrators that need positions and velocities.</summary>
    public virtual bool IsPlainOde => false;

    /// <summary>The default <c>--dt</c> of <c>convergence</c>: coarse enough that the finest level stays above round-off.</summary>
    public virtual double ConvergenceTimeStep => DefaultTimeStep;

    /// <summary>The default <c>--duration</c> of <c>convergence</c>.</summary>
    public virtual double ConvergenceDuration => DefaultDuration;

    /// <summary>The scenario's own options (mass, stiffness, ...), in help order.</summary>
    public abstract IReadOnlyList<Option> PhysicsOptions { get; }

    /// <summary>The integrators of <see cref="IntegratorCatalog"/> that apply to this scenario.</summary>
    public IReadOnlyList<string> Integrators =>
        IntegratorCatalog.Names.Where(n => !(IsPlainOde && IntegratorCatalog.NeedsSecondOrderSystem(n))).ToArray();

    /// <summary>The scenario with the parsed values, or with every default when <paramref name="parse"/> is null.</summary>
    public ScenarioSetup Configure(ParseResult? parse)
    {
        var setup = Build(parse);
        var given = ParameterValues(parse).ToList();
        foreach (var derived in setup.Parameters)
        {
            // A value the setup worked out (a chain's default starting heights) replaces the option's "unset".
            given.RemoveAll(p => p.Key == derived.Key);
            given.Add(derived);
        }

        setup.Parameters = given;
        return setup;
    }

    /// <summary>The options' values, for the JSON header: option name without dashes, and value (unset options left out).</summary>
    public IReadOnlyList<KeyValuePair<string, object>> ParameterValues(ParseResult? parse) =>
        PhysicsOptions
            .Select(o => new KeyValuePair<string, object?>(o.Name.TrimStart('-'), ValueOf(parse, o)))
            .Where(p => p.Value is not null)
            .Select(p => new KeyValuePair<string, object>(p.Key, p.Value!))
            .ToArray();

    /// <summary>Builds the setup; <paramref name="parse"/> is null for all defaults.</summary>
    protected abstract ScenarioSetup Build(ParseResult? parse);

    /// <summary>The value given on the command line, or the option's default.</summary>
    protected static T Value<T>(ParseResult? parse, Option<T> option) =>
        parse is null ? (T)option.GetDefaultValue()! : parse.GetValue(option)!;

    /// <summary>The value given on the command line, or null (options without a fixed default).</summary>
    protected static double? Value(ParseResult? parse, Option<double?> option) => parse?.GetValue(option);

    private static object? ValueOf(ParseResult? parse, Option option) => option switch
    {
        Option<double> d => Value(parse, d),
        Option<double?> n => Value(parse, n),
        Option<string> s => Value(parse, s),
        _ => null,
    };
}
