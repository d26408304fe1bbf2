using System;
using System.IO;
using System.Linq;
using System.Reflection;
using System.Reflection.Metadata;
using System.Reflection.Metadata.Ecma335;
using System.Reflection.PortableExecutable;
using System.Runtime.Versioning;

namespace ParticlePhysics.Tests.Packaging;

/// <summary>The core stays loadable by Unity: netstandard2.1 and nothing else.</summary>
public class CoreAssemblyTests
{
    [Fact]
    public void The_core_assembly_references_nothing_but_netstandard()
    {
        var assembly = typeof(ParticleWorld).Assembly;
        var references = assembly.GetReferencedAssemblies().Select(r => r.Name).ToArray();
        Assert.Equal(new[] { "netstandard" }, references);
        var netstandard = assembly.GetReferencedAssemblies().Single();
        Assert.Equal(new Version(2, 1, 0, 0), netstandard.Version);
    }

    [Fact]
    public void The_core_assembly_targets_netstandard_2_1_and_its_metadata_agrees()
    {
        var assembly = typeof(ParticleWorld).Assembly;
        Assert.Equal(".NETStandard,Version=v2.1", assembly.GetCustomAttribute<TargetFrameworkAttribute>()?.FrameworkName);

        // Read the file itself too: no assembly reference, no module reference (P/Invoke) and no embedded resources.
        using var stream = File.OpenRead(assembly.Location);
        using var pe = new PEReader(stream);
        var metadata = pe.GetMetadataReader();
        var names = metadata.AssemblyReferences.Select(h => metadata.GetString(metadata.GetAssemblyReference(h).Name)).ToArray();
        Assert.Equal(new[] { "netstandard" }, names);
        Assert.Equal(0, metadata.GetTableRowCount(TableIndex.ModuleRef));
        Assert.Empty(metadata.ManifestResources.Cast<ManifestResourceHandle>());
    }
}
