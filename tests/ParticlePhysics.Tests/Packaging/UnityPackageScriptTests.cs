using System;
using System.Collections.Generic;
using System.Diagnostics;
using System.IO;
using System.Linq;
using System.Text.Json;
using System.Text.RegularExpressions;

namespace ParticlePhysics.Tests.Packaging;

/// <summary>tools/make-unity-package.py lays out a UPM folder with stable .meta GUIDs (needs python3 on PATH).</summary>
public class UnityPackageScriptTests
{
    private static readonly string[] _expectedFiles =
    {
        "CHANGELOG.md", "CHANGELOG.md.meta",
        "Documentation~/unity.md",
        "LICENSE.md", "LICENSE.md.meta",
        "README.md", "README.md.meta",
        "Runtime.meta",
        "Runtime/ParticlePhysics.dll", "Runtime/ParticlePhysics.dll.meta",
        "Runtime/ParticlePhysics.xml", "Runtime/ParticlePhysics.xml.meta",
        "Runtime/ParticlePhysics.Scenes.dll", "Runtime/ParticlePhysics.Scenes.dll.meta",
        "Runtime/ParticlePhysics.Scenes.xml", "Runtime/ParticlePhysics.Scenes.xml.meta",
        "Samples~/Cloth/SimulatedCloth.cs", "Samples~/Cloth/SimulatedCloth.cs.meta",
        "Samples~/MeshCloth/MeshCloth.cs", "Samples~/MeshCloth/MeshCloth.cs.meta",
        "package.json", "package.json.meta",
    };

    [Fact]
    public void The_script_lays_out_a_unity_package_with_the_same_guids_every_time()
    {
        var root = RepositoryRoot();
        var dll = typeof(ParticleWorld).Assembly.Location;
        var output = Path.Combine(Path.GetTempPath(), "pp-upm-" + Guid.NewGuid().ToString("N"));
        try
        {
            var first = Guids(RunScript(root, dll, Path.Combine(output, "a")));
            var package = RunScript(root, dll, Path.Combine(output, "b"));
            var second = Guids(package);
            Assert.Equal(first, second);
            Assert.Equal(first.Count, first.Values.Distinct().Count());
            Assert.All(first.Values, g => Assert.Matches("^[0-9a-f]{32}$", g));

            var files = Directory.GetFiles(package, "*", SearchOption.AllDirectories)
                .Select(f => Path.GetRelativePath(package, f).Replace('\\', '/'))
                .OrderBy(f => f, StringComparer.Ordinal)
                .ToArray();
            Assert.Equal(_expectedFiles.OrderBy(f => f, StringComparer.Ordinal), files);

            using var manifest = JsonDocument.Parse(File.ReadAllText(Path.Combine(package, "package.json")));
            var json = manifest.RootElement;
            Assert.Equal("com.particlephysics.core", json.GetProperty("name").GetString());
            Assert.Equal(CsprojVersion(root), json.GetProperty("version").GetString());
            Assert.Equal("2021.3", json.GetProperty("unity").GetString());
            Assert.Equal("MIT", json.GetProperty("license").GetString());
            Assert.False(string.IsNullOrWhiteSpace(json.GetProperty("displayName").GetString()));
            Assert.False(string.IsNullOrWhiteSpace(json.GetProperty("description").GetString()));
            var samples = json.GetProperty("samples").EnumerateArray().ToArray();
            Assert.Equal(new[] { "Samples~/Cloth", "Samples~/MeshCloth" }, samples.Select(s => s.GetProperty("path").GetString()));
            Assert.All(samples, sample =>
            {
                Assert.False(string.IsNullOrWhiteSpace(sample.GetProperty("displayName").GetString()));
                Assert.False(string.IsNullOrWhiteSpace(sample.GetProperty("description").GetString()));
            });

            // The shipped script is the one the tests compile; the README is the package users' one.
            Assert.Equal(
                File.ReadAllText(Path.Combine(root, "samples/unity/Cloth/SimulatedCloth.cs")),
                File.ReadAllText(Path.Combine(package, "Samples~/Cloth/SimulatedCloth.cs")));
            Assert.Contains("MonoImporter:", File.ReadAllText(Path.Combine(package, "Samples~/Cloth/SimulatedCloth.cs.meta")), StringComparison.Ordinal);
            Assert.Equal(
                File.ReadAllText(Path.Combine(root, "samples/unity/MeshCloth/MeshCloth.cs")),
                File.ReadAllText(Path.Combine(package, "Samples~/MeshCloth/MeshCloth.cs")));
            Assert.Equal(
                File.ReadAllText(Path.Combine(root, "src/ParticlePhysics/README.md")),
                File.ReadAllText(Path.Combine(package, "README.md")));

            var pluginMeta = File.ReadAllText(Path.Combine(package, "Runtime/ParticlePhysics.dll.meta"));
            Assert.Contains("PluginImporter:", pluginMeta, StringComparison.Ordinal);
            Assert.Contains("      Any:\n    second:\n      enabled: 1", pluginMeta, StringComparison.Ordinal);
            Assert.Contains("folderAsset: yes", File.ReadAllText(Path.Combine(package, "Runtime.meta")), StringComparison.Ordinal);
            Assert.Equal(File.ReadAllBytes(dll), File.ReadAllBytes(Path.Combine(package, "Runtime/ParticlePhysics.dll")));
            var scenes = typeof(ParticlePhysics.Scenes.Scene).Assembly.Location;
            Assert.Equal(File.ReadAllBytes(scenes), File.ReadAllBytes(Path.Combine(package, "Runtime/ParticlePhysics.Scenes.dll")));
            Assert.Contains("PluginImporter:", File.ReadAllText(Path.Combine(package, "Runtime/ParticlePhysics.Scenes.dll.meta")), StringComparison.Ordinal);
        }
        finally
        {
            if (Directory.Exists(output))
            {
                Directory.Delete(output, recursive: true);
            }
        }
    }

    private static string RunScript(string root, string dll, string output)
    {
        var start = new ProcessStartInfo("python3")
        {
            RedirectStandardOutput = true,
            RedirectStandardError = true,
            WorkingDirectory = root,
        };
        foreach (var argument in new[] { Path.Combine(root, "tools", "make-unity-package.py"), "--dll", dll, "--out", output })
        {
            start.ArgumentList.Add(argument);
        }

        using var process = Process.Start(start) ?? throw new InvalidOperationException("python3 did not start");
        var stdout = process.StandardOutput.ReadToEnd();
        var stderr = process.StandardError.ReadToEnd();
        process.WaitForExit();
        Assert.True(process.ExitCode == 0, $"make-unity-package.py exited with {process.ExitCode}: {stderr}");
        return stdout.Trim();
    }

    private static Dictionary<string, string> Guids(string package)
    {
        var guids = new Dictionary<string, string>(StringComparer.Ordinal);
        foreach (var meta in Directory.GetFiles(package, "*.meta", SearchOption.AllDirectories))
        {
            var match = Regex.Match(File.ReadAllText(meta), "^guid: (\\S+)$", RegexOptions.Multiline);
            Assert.True(match.Success, $"{meta} has no guid");
            guids[Path.GetRelativePath(package, meta)] = match.Groups[1].Value;
        }

        return guids;
    }

    private static string CsprojVersion(string root)
    {
        var csproj = File.ReadAllText(Path.Combine(root, "src", "ParticlePhysics", "ParticlePhysics.csproj"));
        return Regex.Match(csproj, "<Version>([^<]+)</Version>").Groups[1].Value;
    }

    private static string RepositoryRoot()
    {
        for (var dir = new DirectoryInfo(AppContext.BaseDirectory); dir is not null; dir = dir.Parent)
        {
            if (File.Exists(Path.Combine(dir.FullName, "tools", "make-unity-package.py")))
            {
                return dir.FullName;
            }
        }

        throw new InvalidOperationException("tools/make-unity-package.py not found above " + AppContext.BaseDirectory);
    }
}
