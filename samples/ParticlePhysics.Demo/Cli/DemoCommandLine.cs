using System.Collections.Generic;
using System.CommandLine;
using System.Linq;
using ParticlePhysics.Demo.Scenarios;

namespace ParticlePhysics.Demo.Cli;

/// <summary>
/// The command tree: one command per scenario, <c>convergence SCENARIO</c>, and the tour when there are no
/// arguments. Parse errors become one <c>error:</c> line (see <see cref="ParseErrors"/>), not the library's
/// multi-line report.
/// </summary>
internal static class DemoCommandLine
{
    /// <summary>A fresh set of scenario definitions (each owns its option objects, so each command gets its own).</summary>
    public static IReadOnlyList<ScenarioDefinition> Scenarios() => new ScenarioDefinition[]
    {
        new FreeFallDefinition(),
        new MassSpringDamperDefinition(),
        new TwoMassChainDefinition(),
        new ClothDefinition(),
        new PendulumDefinition(),
        new HangingChainDefinition(),
        new ScalarOdeDefinition(),
        new BouncingBallDefinition(),
        new CollisionDefinition(),
        new DrapeDefinition(),
    };

    public static RootCommand Build(DemoContext context)
    {
        var root = new RootCommand(
            "ParticlePhysics demo: the course's scenarios (free fall, mass-spring-damper, two-mass chain, cloth, pendulum, hanging chain, scalar ODE, "
            + "bouncing ball, collision, drape) "
            + "with any integrator, printed as a table, csv or json, optionally plotted as SVG; 'scene FILE.json' runs a scene file of your own. "
            + "With no arguments, runs every scenario briefly and prints one summary table. Units are SI.");
        foreach (var scenario in Scenarios())
        {
            root.Add(ScenarioCommand.Create(scenario, context));
        }

        root.Add(ConvergenceCommand.Create(Scenarios(), context));
        root.Add(SceneCommand.Create(context));
        root.SetAction(_ => SummaryRun.Execute(Scenarios(), context));
        return root;
    }

    /// <summary>The names a user may type as the first argument.</summary>
    public static IEnumerable<string> CommandNames(RootCommand root) => root.Subcommands.Select(c => c.Name);
}
