using System.IO;
using System.Linq;
using System.Text.RegularExpressions;
using ParticlePhysics.Tests.Engine;

namespace ParticlePhysics.Tests.Architecture;

/// <summary>
/// docs/architecture.md's reading order (the three paths through a step, as <c>file:Member</c> anchors) names files
/// that exist and members they declare, so that the map keeps up with the code it maps.
/// </summary>
public class ReadingOrderTests
{
    [Fact]
    public void Every_anchor_of_the_reading_order_is_a_member_of_its_file()
    {
        var root = ReadmeExamplesTests.RepositoryRoot();
        var page = File.ReadAllText(Path.Combine(root, "docs", "architecture.md"));
        var start = page.IndexOf("## Reading order", System.StringComparison.Ordinal);
        Assert.True(start >= 0, "docs/architecture.md has no section '## Reading order'");
        var end = page.IndexOf("\n## ", start + 1, System.StringComparison.Ordinal);
        var section = page[start..(end < 0 ? page.Length : end)];

        var anchors = Regex.Matches(section, @"`([\w./]+\.cs):(\w+)`").Select(m => (File: m.Groups[1].Value, Member: m.Groups[2].Value)).ToArray();
        Assert.True(anchors.Length >= 30, $"{anchors.Length} anchors");
        foreach (var path in new[] { "Force-based", "Implicit", "Position-based" })
        {
            Assert.Contains("**" + path + "**", section, System.StringComparison.Ordinal);
        }

        var missing = anchors.Where(a => !Declares(Path.Combine(root, "src", "ParticlePhysics", a.File), a.Member))
            .Select(a => $"{a.File}:{a.Member}").Distinct().ToArray();
        Assert.True(missing.Length == 0, "anchors that name no member of their file: " + string.Join(", ", missing));
    }

    // A member is declared at the class's indentation (four spaces, the repository's layout), not in a comment.
    private static bool Declares(string file, string member) =>
        File.Exists(file) && File.ReadLines(file).Any(line =>
            Regex.IsMatch(line, @"^    [^\s/\[].*\b" + Regex.Escape(member) + @"\s*(<[^>]*>)?\s*(\(|=>|\{|$)"));
}
