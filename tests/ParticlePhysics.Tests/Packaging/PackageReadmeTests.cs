using System;
using System.IO;
using System.Linq;
using System.Text.RegularExpressions;
using ParticlePhysics.Tests.Engine;

namespace ParticlePhysics.Tests.Packaging;

/// <summary>
/// The NuGet package's README (src/ParticlePhysics/README.md) is for people who installed the package: it installs
/// the current version, and every link is absolute, into the repository of the csproj's RepositoryUrl, at a file that
/// exists. (Its quickstart is checked against the tested code by ReadmeExamplesTests.)
/// </summary>
public partial class PackageReadmeTests
{
    private static readonly string _root = ReadmeExamplesTests.RepositoryRoot();
    private static readonly string _csproj = File.ReadAllText(Path.Combine(_root, "src/ParticlePhysics/ParticlePhysics.csproj"));
    private static readonly string _readme = File.ReadAllText(Path.Combine(_root, "src/ParticlePhysics/README.md"));

    [Fact]
    public void The_package_packs_its_own_readme()
    {
        Assert.Contains("<PackageReadmeFile>README.md</PackageReadmeFile>", _csproj, StringComparison.Ordinal);
        Assert.Contains("<None Update=\"README.md\" Pack=\"true\" PackagePath=\"/\" />", _csproj, StringComparison.Ordinal);
        Assert.DoesNotContain("../../README.md", _csproj, StringComparison.Ordinal);
    }

    [Fact]
    public void The_install_command_names_the_csproj_version()
    {
        var version = Regex.Match(_csproj, "<Version>([^<]+)</Version>").Groups[1].Value;
        Assert.Contains($"dotnet add package ParticlePhysics --version {version}", _readme, StringComparison.Ordinal);
        Assert.Contains($"## {version}", File.ReadAllText(Path.Combine(_root, "CHANGELOG.md")), StringComparison.Ordinal);
    }

    [Fact]
    public void Every_link_is_absolute_and_those_into_the_repository_name_files_that_exist()
    {
        var repository = Regex.Match(_csproj, "<RepositoryUrl>([^<]+)</RepositoryUrl>").Groups[1].Value;
        var links = MarkdownLink().Matches(_readme).Select(m => m.Groups["target"].Value).ToArray();
        Assert.NotEmpty(links);
        foreach (var link in links)
        {
            Assert.StartsWith("https://", link, StringComparison.Ordinal);
            if (link.StartsWith(repository + "/blob/main/", StringComparison.Ordinal))
            {
                var file = link[(repository + "/blob/main/").Length..];
                Assert.True(File.Exists(Path.Combine(_root, file)), $"{link}: no {file} in the repository");
            }
            else
            {
                Assert.Equal(repository, link);
            }
        }

        Assert.Contains(links, l => l.EndsWith("/docs/unity.md", StringComparison.Ordinal));
    }

    [GeneratedRegex(@"\]\((?<target>[^)\s]+)\)")]
    private static partial Regex MarkdownLink();
}
