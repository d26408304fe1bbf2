using System.Linq;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Packaging;

/// <summary>
/// Unity's Mono declares ReadOnlySpan&lt;T&gt;'s indexer and GetPinnableReference as returning <c>ref T</c>, while the
/// netstandard2.1 reference assembly says <c>ref readonly T</c>, which the compiler encodes as a modreq(InAttribute)
/// on the return type. A call site with that modreq does not bind on Mono (MissingMethodException at the first
/// step), so the core and the scene loader (both shipped to Unity) must reference no member of another assembly whose return carries it.
/// </summary>
public class MonoCompatibilityTests
{
    [Theory]
    [InlineData("the core")]
    [InlineData("the scene loader")]
    public void The_product_calls_no_ref_readonly_returning_member_of_another_assembly(string assembly)
    {
        using var metadata = new CoreMetadata(assembly == "the core" ? typeof(ParticleWorld).Assembly : typeof(ParticlePhysics.Scenes.Scene).Assembly);
        var offending = metadata.ExternalMemberReferences()
            .Where(m => m.Returns.Contains("modreq(System.Runtime.InteropServices.InAttribute)"))
            .Select(m => $"{m.Member}: {m.Signature}, called by {string.Join(", ", metadata.MethodsUsing(m.Handle))}")
            .ToArray();
        Assert.True(offending.Length == 0, "Members that do not bind on Mono:\n" + string.Join("\n", offending));
    }

    [Fact]
    public void The_check_reads_member_signatures_with_their_modifiers()
    {
        // The core does call Span<double>'s indexer (plain ref T): the reader must see it, without a modreq.
        using var metadata = new CoreMetadata();
        var indexer = metadata.ExternalMemberReferences().First(m => m.Member == "System.Span`1<Double>::get_Item");
        Assert.Equal("!0& (Int32)", indexer.Signature);
    }
}
