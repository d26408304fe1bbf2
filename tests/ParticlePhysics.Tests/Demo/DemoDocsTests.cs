using System;
using System.IO;
using System.Linq;
using ParticlePhysics.Tests.Engine;

namespace ParticlePhysics.Tests.Demo;

/// <summary>
/// What the docs show the demo printing is what it prints: the tour's table in README.md and docs/demo.md, and the
/// error lines of docs/demo.md's examples.
/// </summary>
public sealed class DemoDocsTests
{
    private static readonly string _root = ReadmeExamplesTests.RepositoryRoot();

    [Theory]
    [InlineData("README.md")]
    [InlineData("docs/demo.md")]
    public void The_tour_table_in_the_docs_is_the_programs(string file)
    {
        var actual = Table(DemoProcess.Run().Output.Split('\n').Select(l => l.TrimEnd('\r')).ToArray());

        var documented = Table(File.ReadAllLines(Path.Combine(_root, file)).Select(l => l.StartsWith("    ", StringComparison.Ordinal) ? l[4..] : l).ToArray());

        Assert.Equal(actual, documented);
    }

    [Fact]
    public void The_error_examples_in_the_docs_are_the_programs()
    {
        var lines = File.ReadAllLines(Path.Combine(_root, "docs", "demo.md"));
        const string prompt = "    $ dotnet run --project samples/ParticlePhysics.Demo -- ";
        var examples = 0;
        for (var i = 0; i + 1 < lines.Length; i++)
        {
            if (!lines[i].StartsWith(prompt, StringComparison.Ordinal) || !lines[i + 1].StartsWith("    error: ", StringComparison.Ordinal))
            {
                continue;
            }

            var command = lines[i][prompt.Length..];
            var redirect = command.IndexOf(" >", StringComparison.Ordinal);
            var args = (redirect < 0 ? command : command[..redirect]).Split(' ', StringSplitOptions.RemoveEmptyEntries);

            var result = DemoProcess.Run(args);

            Assert.Equal(lines[i + 1][4..], result.ErrorLines.Single());
            examples++;
        }

        Assert.True(examples >= 4, $"{examples} examples found");
    }

    // From the table's header to its last row (the scenarios' rows, whatever comes before and after).
    private static string[] Table(string[] lines)
    {
        var start = Array.FindIndex(lines, l => l.StartsWith("scenario  ", StringComparison.Ordinal) && l.Contains("integrator", StringComparison.Ordinal));
        Assert.True(start >= 0, "no tour table");
        var end = start + 1;
        while (end < lines.Length && lines[end].Length > 0 && !lines[end].StartsWith("```", StringComparison.Ordinal))
        {
            end++;
        }

        return lines[start..end].Select(l => l.TrimEnd()).ToArray();
    }
}
