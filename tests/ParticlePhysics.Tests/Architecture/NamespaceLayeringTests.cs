using System.Collections.Generic;
using System.IO;
using System.Linq;
using System.Text.RegularExpressions;
using ParticlePhysics.Tests.Engine;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Architecture;

/// <summary>
/// The core's folders are layers: each namespace may use the ones below it and never the other way round, so that
/// a reader can take them in order (docs/architecture.md). Read from the built assembly: signatures and IL.
/// </summary>
public class NamespaceLayeringTests
{
    [Fact]
    public void No_two_namespaces_of_the_core_use_each_other_even_through_others()
    {
        var edges = NamespaceEdges();
        var cycle = FindCycle(edges.Keys.Select(e => e.From).Concat(edges.Keys.Select(e => e.To)).Distinct(), edges);
        Assert.True(
            cycle is null,
            cycle is null ? string.Empty : "The core's namespaces form a cycle: " + string.Join(
                "; ", cycle.Zip(cycle.Skip(1).Append(cycle[0]), (a, b) => $"{a} uses {b} ({edges[(a, b)]})")));
    }

    [Fact]
    public void The_world_and_its_contracts_use_only_the_leaf_namespaces()
    {
        // The root namespace holds the world and the interfaces the folders implement; it may use Internal (the
        // library's own contracts between its folders), Numerics and Parallel, which use nothing of the core.
        var edges = NamespaceEdges();
        var fromRoot = edges.Keys.Where(e => e.From == "ParticlePhysics").Select(e => e.To).OrderBy(n => n).ToArray();
        Assert.Equal(new[] { "ParticlePhysics.Internal", "ParticlePhysics.Numerics", "ParticlePhysics.Parallel" }, fromRoot);
        Assert.DoesNotContain(
            edges.Keys, e => e.From is "ParticlePhysics.Internal" or "ParticlePhysics.Numerics" or "ParticlePhysics.Parallel");
    }

    [Fact]
    public void The_layering_check_sees_uses_inside_method_bodies()
    {
        // The world's Step calls DoubleChecks (Numerics) only inside its body: the reader must find that edge.
        var edges = NamespaceEdges();
        Assert.Contains(("ParticlePhysics", "ParticlePhysics.Numerics"), edges.Keys);
        Assert.Contains(("ParticlePhysics.Cloth", "ParticlePhysics.Forces"), edges.Keys);
    }

    [Fact]
    public void The_architecture_page_names_every_namespace_and_allows_every_use()
    {
        // docs/architecture.md has a table: | `Folder/` (or root) | what lives there | may use |. The tree and the
        // page must agree: every namespace of the assembly has a row, and every use is one its row allows. A folder
        // inside a folder (`Integrators/Multigrid/`) is the namespace ParticlePhysics.Integrators.Multigrid.
        var page = File.ReadAllText(Path.Combine(ReadmeExamplesTests.RepositoryRoot(), "docs", "architecture.md"));
        var allowed = new Dictionary<string, HashSet<string>>();
        static string Namespace(string folder) => "ParticlePhysics." + folder.Replace('/', '.');
        foreach (Match row in Regex.Matches(page, @"^\| (root \(`ParticlePhysics`\)|`([\w/]+)/`) \|[^|]*\| ([^|]*) \|$", RegexOptions.Multiline))
        {
            var name = row.Groups[2].Success ? Namespace(row.Groups[2].Value) : "ParticlePhysics";
            var uses = row.Groups[3].Value.Split(',').Select(u => u.Trim())
                .Where(u => u.Length > 0 && u != "nothing of the core")
                .Select(u => u == "root" ? "ParticlePhysics" : Namespace(u));
            allowed[name] = new HashSet<string>(uses);
        }

        var edges = NamespaceEdges();
        using var metadata = new CoreMetadata();
        var namespaces = metadata.Reader.TypeDefinitions.Select(metadata.NamespaceOf)
            .Where(n => n.StartsWith("ParticlePhysics", System.StringComparison.Ordinal)).Distinct().OrderBy(n => n);
        Assert.Equal(namespaces, allowed.Keys.OrderBy(n => n));
        var forbidden = edges.Where(e => !allowed[e.Key.From].Contains(e.Key.To)).Select(e => e.Value).ToArray();
        Assert.True(forbidden.Length == 0, "Uses the architecture page does not allow: " + string.Join("; ", forbidden));
    }

    /// <summary>Every pair of distinct namespaces (A uses B), with one example of a type of A using a type of B.</summary>
    private static Dictionary<(string From, string To), string> NamespaceEdges()
    {
        using var metadata = new CoreMetadata();
        var edges = new Dictionary<(string, string), string>();
        foreach (var type in metadata.Reader.TypeDefinitions)
        {
            var from = metadata.NamespaceOf(type);
            if (from.Length == 0)
            {
                continue; // <Module> and compiler-generated types without a namespace
            }

            foreach (var used in metadata.TypesUsedBy(type))
            {
                var to = metadata.NamespaceOf(used);
                if (to.Length > 0 && to != from && !edges.ContainsKey((from, to)))
                {
                    edges[(from, to)] = $"{metadata.NameOf(type)} uses {metadata.NameOf(used)}";
                }
            }
        }

        return edges;
    }

    private static List<string>? FindCycle(IEnumerable<string> nodes, Dictionary<(string From, string To), string> edges)
    {
        var state = new Dictionary<string, int>(); // 1: on the current path, 2: done
        var path = new List<string>();
        List<string>? Visit(string node)
        {
            state[node] = 1;
            path.Add(node);
            foreach (var next in edges.Keys.Where(e => e.From == node).Select(e => e.To))
            {
                if (state.GetValueOrDefault(next) == 1)
                {
                    return path.Skip(path.IndexOf(next)).ToList();
                }

                if (state.GetValueOrDefault(next) == 0 && Visit(next) is { } found)
                {
                    return found;
                }
            }

            path.RemoveAt(path.Count - 1);
            state[node] = 2;
            return null;
        }

        foreach (var node in nodes)
        {
            if (state.GetValueOrDefault(node) == 0 && Visit(node) is { } cycle)
            {
                return cycle;
            }
        }

        return null;
    }
}
