using System.CommandLine;
using System.Linq;
using ParticlePhysics.Demo.Scenarios;

namespace ParticlePhysics.Demo.Cli;

/// <summary>
/// Turns System.CommandLine's parse errors into the contract's single line: what was wrong, the value, and what
/// is allowed (with a suggestion for a near miss).
/// </summary>
internal static class ParseErrors
{
    /// <summary>The message (without "error: ") for the first problem of <paramref name="parse"/>.</summary>
    public static string Describe(ParseResult parse, RootCommand root)
    {
        var command = parse.CommandResult.Command;
        var path = ReferenceEquals(command, root) ? string.Empty : Path(parse);
        if (parse.UnmatchedTokens.FirstOrDefault() is { } token)
        {
            if (token.StartsWith('-'))
            {
                var names = command.Options.SelectMany(o => o.Aliases.Append(o.Name)).Distinct().ToArray();
                var where = path.Length == 0 ? "the demo" : path;
                return $"unknown option '{token}' for {where}{Suggestions.DidYouMean(token, names)}; run '{(path + " --help").Trim()}' to list the options.";
            }

            if (ReferenceEquals(command, root))
            {
                var scenarios = DemoCommandLine.CommandNames(root).ToArray();
                return $"unknown scenario '{token}'{Suggestions.DidYouMean(token, scenarios)}; expected one of: {string.Join(", ", scenarios)}.";
            }

            if (command.Name == ConvergenceCommand.Name)
            {
                return UnknownConvergenceScenario(command, token);
            }

            return $"unexpected argument '{token}' for {path}; options start with '--' (run '{path} --help').";
        }

        if (command.Name == ConvergenceCommand.Name)
        {
            return $"convergence needs a scenario with an exact solution: one of {string.Join(", ", command.Subcommands.Select(c => c.Name))}.";
        }

        var message = parse.Errors[0].Message.Replace('\n', ' ').Replace('\r', ' ');
        if (command.Name == SceneCommand.Name && message.StartsWith("Required argument missing", System.StringComparison.Ordinal))
        {
            return "scene needs a scene file: scene FILE.json [options] (samples/scenes/ has examples; docs/scenes.md describes the format).";
        }

        const string missing = "Required argument missing for option: '";
        if (message.StartsWith(missing, System.StringComparison.Ordinal))
        {
            var option = message[missing.Length..].TrimEnd('.', '\'');
            return $"{option} needs a value; run '{(path + " --help").Trim()}' to see what it takes.";
        }

        return message;
    }

    private static string UnknownConvergenceScenario(Command convergence, string token)
    {
        var names = convergence.Subcommands.Select(c => c.Name).ToArray();
        var why = ConvergenceCommand.Refusal(token) is { } refusal ? $" ({refusal})" : Suggestions.DidYouMean(token, names);
        return $"convergence cannot run '{token}'{why}; expected one of: {string.Join(", ", names)}.";
    }

    private static string Path(ParseResult parse)
    {
        var names = new System.Collections.Generic.List<string>();
        for (var result = parse.CommandResult; result.Parent is System.CommandLine.Parsing.CommandResult parent; result = parent)
        {
            names.Insert(0, result.Command.Name);
        }

        return string.Join(' ', names);
    }
}
