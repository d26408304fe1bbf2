using System;
using System.Collections.Generic;
using System.Collections.Immutable;
using System.IO;
using System.Linq;
using System.Reflection;
using Microsoft.CodeAnalysis;
using Microsoft.CodeAnalysis.CSharp;
using ParticlePhysics.Tests.Engine;

namespace ParticlePhysics.Tests.Unity;

/// <summary>
/// Compiles scripts the way Unity compiles a project's scripts (Roslyn, C# 9, no nullable context, no implicit usings,
/// unsafe code off, API level .NET Standard 2.1: netstandard.dll is the one framework reference) against the built
/// ParticlePhysics.dll and the stand-in UnityEngine of <c>tests/unity/UnityEngine.cs</c>.
/// </summary>
internal static class UnityScripts
{
    public const string SamplePath = "samples/unity/Cloth/SimulatedCloth.cs";
    public const string StandInPath = "tests/unity/UnityEngine.cs";
    public const string MeshClothPath = "samples/unity/MeshCloth/MeshCloth.cs";

    private static readonly Lazy<byte[]> _standIn = new(() => CompileOrThrow("UnityEngine", StandInPath));
    private static readonly Lazy<byte[]> _sample = new(() => CompileOrThrow("Assembly-CSharp", SamplePath));
    private static readonly Lazy<byte[]> _meshCloth = new(() => CompileOrThrow("Assembly-CSharp", MeshClothPath));

    /// <summary>Unity's parse options: C# 9, no preprocessor symbols of ours.</summary>
    public static CSharpParseOptions ParseOptions { get; } = new(LanguageVersion.CSharp9);

    /// <summary>The stand-in UnityEngine.dll, compiled once.</summary>
    public static byte[] StandInImage => _standIn.Value;

    /// <summary>The sample's script assembly (Unity's Assembly-CSharp), compiled once.</summary>
    public static byte[] SampleImage => _sample.Value;

    /// <summary>The mesh cloth sample's script assembly, compiled once.</summary>
    public static byte[] MeshClothImage => _meshCloth.Value;

    /// <summary>netstandard.dll 2.1 (the reference assembly of the NETStandard.Library.Ref package).</summary>
    public static MetadataReference NetStandard { get; } = MetadataReference.CreateFromFile(NetStandardPath());

    /// <summary>The ParticlePhysics.dll these tests run against.</summary>
    public static MetadataReference Core { get; } = MetadataReference.CreateFromFile(typeof(ParticleWorld).Assembly.Location);

    public static string ReadRepositoryFile(string relativePath) =>
        File.ReadAllText(Path.Combine(ReadmeExamplesTests.RepositoryRoot(), relativePath));

    /// <summary>
    /// Compiles <paramref name="sources"/> (path, text) into an assembly with Unity's settings, against netstandard,
    /// the stand-in UnityEngine (unless this is the stand-in) and <paramref name="references"/> (by default the core).
    /// </summary>
    public static (byte[]? Image, ImmutableArray<Diagnostic> Diagnostics) Compile(
        string assemblyName, IEnumerable<(string Path, string Text)> sources, IEnumerable<MetadataReference>? references = null)
    {
        var trees = sources.Select(s => CSharpSyntaxTree.ParseText(s.Text, ParseOptions, s.Path)).ToArray();
        var all = new List<MetadataReference> { NetStandard };
        if (assemblyName != "UnityEngine")
        {
            all.Add(MetadataReference.CreateFromImage(StandInImage));
            all.AddRange(references ?? new[] { Core });
        }

        var options = new CSharpCompilationOptions(
            OutputKind.DynamicallyLinkedLibrary,
            nullableContextOptions: NullableContextOptions.Disable,
            allowUnsafe: false,
            warningLevel: 4,
            deterministic: true);
        var compilation = CSharpCompilation.Create(assemblyName, trees, all, options);
        using var image = new MemoryStream();
        var result = compilation.Emit(image);
        var diagnostics = result.Diagnostics.Where(d => d.Severity >= DiagnosticSeverity.Warning).ToImmutableArray();
        return (result.Success ? image.ToArray() : null, diagnostics);
    }

    /// <summary>The diagnostics as lines a test failure can show.</summary>
    public static string Describe(IEnumerable<Diagnostic> diagnostics) =>
        string.Join("\n", diagnostics.Select(d => d.ToString()));

    private static byte[] CompileOrThrow(string assemblyName, string path)
    {
        var (image, diagnostics) = Compile(assemblyName, new[] { (path, ReadRepositoryFile(path)) });
        if (image is null || diagnostics.Length > 0)
        {
            throw new InvalidOperationException($"{path} does not compile cleanly with Unity's settings:\n{Describe(diagnostics)}");
        }

        return image;
    }

    private static string NetStandardPath()
    {
        var path = typeof(UnityScripts).Assembly.GetCustomAttributes<AssemblyMetadataAttribute>()
            .Single(a => a.Key == "NetStandardReference").Value!;
        if (!File.Exists(path))
        {
            throw new InvalidOperationException(
                $"{path} is missing: the test project downloads NETStandard.Library.Ref 2.1.0 at restore (PackageDownload).");
        }

        return path;
    }
}
