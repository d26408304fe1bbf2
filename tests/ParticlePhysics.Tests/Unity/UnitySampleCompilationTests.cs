using System;
using System.Linq;
using System.Reflection;
using System.Text.RegularExpressions;

namespace ParticlePhysics.Tests.Unity;

/// <summary>
/// The Unity sample (<c>samples/unity/Cloth/SimulatedCloth.cs</c>, shipped in the package's Samples~) compiles as Unity
/// compiles it, against a stand-in UnityEngine whose Mesh takes what Unity's takes, and it is the code docs/unity.md
/// shows.
/// </summary>
public partial class UnitySampleCompilationTests
{
    /// <summary>The UnityEngine names our public types must not take (the project brief's list).</summary>
    internal static readonly string[] ForbiddenNames =
    {
        "ParticleSystem", "Cloth", "Collider", "SphereCollider", "BoxCollider", "CapsuleCollider", "Plane", "Ray",
        "Bounds", "Transform", "Rigidbody", "Joint", "SpringJoint", "Mesh", "Time", "Physics", "Vector3", "Quaternion",
        "Matrix4x4", "Color", "Random", "Debug", "Mathf", "Pose", "Camera", "Light", "Collision", "ContactPoint",
        "PhysicMaterial", "WheelCollider", "CharacterController", "MonoBehaviour", "GameObject", "MeshFilter",
    };

    [Fact]
    public void The_sample_compiles_with_unity_settings_without_errors_or_warnings()
    {
        var (image, diagnostics) = UnityScripts.Compile(
            "Assembly-CSharp", new[] { (UnityScripts.SamplePath, UnityScripts.ReadRepositoryFile(UnityScripts.SamplePath)) });
        Assert.True(diagnostics.IsEmpty, UnityScripts.Describe(diagnostics));
        Assert.NotNull(image);
    }

    [Fact]
    public void The_compiler_settings_are_unitys_a_newer_feature_or_an_implicit_using_does_not_compile()
    {
        // C# 10's file-scoped namespace and a script that relies on an implicit `using System;` both fail, as in Unity.
        var (_, newer) = UnityScripts.Compile("Newer", new[] { ("Newer.cs", "namespace A;\npublic class B { }") });
        Assert.Contains(newer, d => d.Id == "CS8773");
        var (_, implicitUsing) = UnityScripts.Compile(
            "Implicit", new[] { ("Implicit.cs", "public class B { public int[] C = new int[1]; public object D() => C.AsSpan(); }") });
        Assert.Contains(implicitUsing, d => d.Id == "CS1061");
    }

    [Fact]
    public void The_stand_in_declares_the_unity_names_that_could_clash_and_what_the_sample_uses()
    {
        var standIn = Assembly.Load(UnityScripts.StandInImage);
        var names = standIn.GetExportedTypes().Where(t => t.Namespace == "UnityEngine").Select(t => t.Name).ToHashSet();
        var missing = ForbiddenNames.Where(n => !names.Contains(n)).ToArray();
        Assert.True(missing.Length == 0, "The stand-in lacks: " + string.Join(", ", missing));
    }

    [Fact]
    public void The_stand_in_mesh_takes_arrays_lists_and_native_arrays_but_no_spans_as_unitys_does()
    {
        var mesh = Assembly.Load(UnityScripts.StandInImage).GetType("UnityEngine.Mesh", throwOnError: true)!;
        foreach (var name in new[] { "SetVertices", "SetNormals" })
        {
            var first = mesh.GetMethods().Where(m => m.Name == name).Select(m => m.GetParameters()[0].ParameterType).ToArray();
            Assert.Contains(first, t => t.IsArray);
            Assert.Contains(first, t => t.IsGenericType && t.GetGenericTypeDefinition().Name == "List`1");
            Assert.Contains(first, t => t.Name == "NativeArray`1");
            Assert.DoesNotContain(first, t => t.Name.Contains("Span", StringComparison.Ordinal));
        }
    }

    [Fact]
    public void Docs_unity_md_shows_the_sample_file_as_it_is()
    {
        var page = UnityScripts.ReadRepositoryFile("docs/unity.md");
        var blocks = FileBlock().Matches(page);
        Assert.Contains(blocks, b => b.Groups["path"].Value == UnityScripts.SamplePath);
        foreach (Match block in blocks)
        {
            var file = UnityScripts.ReadRepositoryFile(block.Groups["path"].Value).Replace("\r\n", "\n", StringComparison.Ordinal);
            Assert.Equal(file, block.Groups["code"].Value.Replace("\r\n", "\n", StringComparison.Ordinal));
        }

        // Every C# block of the page is one of those files: none is code that no compiler saw.
        Assert.Equal(Regex.Matches(page, "```csharp").Count, blocks.Count);
    }

    [GeneratedRegex(@"<!-- file: (?<path>[^ ]+) -->\s*```csharp\r?\n(?<code>.*?)```", RegexOptions.Singleline)]
    private static partial Regex FileBlock();
}
