using System;
using System.IO;
using System.Linq;
using System.Reflection;
using System.Runtime.Loader;
using System.Text;
using Microsoft.CodeAnalysis;

namespace ParticlePhysics.Tests.Unity;

/// <summary>
/// Every public type of the core can be named by its simple name in a Unity script that imports UnityEngine, the usual
/// System namespaces and every namespace of ours, without an alias. The script is written from the built assembly's
/// public types, so a type added later is checked too; a clash fails with CS0104 ("an ambiguous reference").
/// </summary>
public class UnityNameClashTests
{
    private static readonly string[] _systemUsings = { "System", "System.Collections.Generic", "System.IO", "System.Numerics" };

    [Fact]
    public void Every_public_type_of_the_core_compiles_by_its_simple_name_beside_using_UnityEngine()
    {
        var script = ScriptNaming(typeof(ParticleWorld).Assembly);
        var (_, diagnostics) = UnityScripts.Compile("NameClash", new[] { ("NameClash.cs", script) });
        Assert.True(diagnostics.IsEmpty, UnityScripts.Describe(diagnostics) + "\n\n" + script);
        Assert.Contains("typeof(ParticleWorld)", script, StringComparison.Ordinal);
        Assert.Contains("using ParticlePhysics.Cloth;", script, StringComparison.Ordinal);
    }

    [Fact]
    public void The_check_fails_on_a_public_type_named_like_a_unity_type()
    {
        // A library with ParticlePhysics.ParticleSystem, the name this engine had before 0.2.0, and a generic type.
        var (image, built) = UnityScripts.Compile(
            "Clashing",
            new[] { ("Clashing.cs", "namespace ParticlePhysics.Old { public class ParticleSystem { } public class Pool<T> { } }") },
            Array.Empty<MetadataReference>());
        Assert.True(image is not null, UnityScripts.Describe(built));
        var context = new AssemblyLoadContext("clashing", isCollectible: true);
        try
        {
            var clashing = context.LoadFromStream(new MemoryStream(image));
            var script = ScriptNaming(clashing);
            Assert.Contains("typeof(Pool<>)", script, StringComparison.Ordinal);
            var (_, diagnostics) = UnityScripts.Compile(
                "NameClash", new[] { ("NameClash.cs", script) }, new[] { MetadataReference.CreateFromImage(image) });
            var clash = Assert.Single(diagnostics);
            Assert.Equal("CS0104", clash.Id);
            Assert.Contains("UnityEngine.ParticleSystem", clash.GetMessage(), StringComparison.Ordinal);
        }
        finally
        {
            context.Unload();
        }
    }

    /// <summary>A Unity script that imports UnityEngine and every namespace of <paramref name="library"/> and names each public type.</summary>
    internal static string ScriptNaming(Assembly library)
    {
        var types = library.GetExportedTypes()
            .Where(t => !t.IsNested && t.Namespace is not null)
            .OrderBy(t => t.FullName, StringComparer.Ordinal)
            .ToArray();
        var script = new StringBuilder();
        foreach (var name in _systemUsings)
        {
            script.Append("using ").Append(name).Append(";\n");
        }

        script.Append("using UnityEngine;\n");
        foreach (var name in types.Select(t => t.Namespace!).Distinct().OrderBy(n => n, StringComparer.Ordinal))
        {
            script.Append("using ").Append(name).Append(";\n");
        }

        script.Append("\npublic static class EveryPublicTypeBesideUnityEngine\n{\n    public static readonly Type[] Types =\n    {\n");
        foreach (var type in types)
        {
            script.Append("        typeof(").Append(SimpleName(type)).Append("),\n");
        }

        script.Append("    };\n}\n");
        return script.ToString();
    }

    private static string SimpleName(Type type)
    {
        if (!type.IsGenericTypeDefinition)
        {
            return type.Name;
        }

        var name = type.Name[..type.Name.IndexOf('`', StringComparison.Ordinal)];
        return name + "<" + new string(',', type.GetGenericArguments().Length - 1) + ">";
    }
}
