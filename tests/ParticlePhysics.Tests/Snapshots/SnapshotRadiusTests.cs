using System;
using System.Buffers.Binary;
using System.IO;
using ParticlePhysics.Cloth;
using ParticlePhysics.Snapshots;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Snapshots;

/// <summary>Format version 2 carries the particles' radii; version 1 streams (without them) still read, with radius 0.</summary>
public class SnapshotRadiusTests
{
    [Fact]
    public void Radii_travel_through_a_stream_and_are_restored()
    {
        var source = ClothSystem();
        for (var i = 0; i < source.Count; i++)
        {
            source.SetRadius(i, 0.001 * (i + 1));
        }

        var stream = new MemoryStream();
        SimulationSnapshot.Capture(source).WriteTo(stream);
        Assert.Equal(SimulationSnapshot.Capture(source).SerializedLength, stream.Length);
        stream.Position = 0;
        var read = SimulationSnapshot.ReadFrom(stream);
        var target = ClothSystem();
        read.RestoreTo(target);
        Assert.Equal(source.Radii.ToArray(), target.Radii.ToArray());
        Assert.Equal(source.Radii.ToArray(), read.Radii.ToArray());
    }

    [Fact]
    public void A_version_1_stream_reads_with_every_radius_0()
    {
        var source = ClothSystem();
        StateMetrics.Run(source, new ParticlePhysics.Integrators.RungeKutta4(), 0.001, 5);
        var version1 = VersionOne(source);
        var target = ClothSystem();
        target.SetRadius(3, 0.5);
        SimulationSnapshot.ReadFrom(new MemoryStream(version1)).RestoreTo(target);
        Assert.Equal(StateMetrics.BitHash(source.State), StateMetrics.BitHash(target.State));
        Assert.All(target.Radii.ToArray(), r => Assert.Equal(0.0, r));
    }

    [Fact]
    public void A_negative_or_non_finite_radius_in_a_stream_is_refused()
    {
        var source = ClothSystem();
        var stream = new MemoryStream();
        SimulationSnapshot.Capture(source).WriteTo(stream);
        var bytes = stream.ToArray();
        var radii = 28 + (57 * source.Count);
        foreach (var bad in new[] { -1.0, double.NaN, double.PositiveInfinity })
        {
            var copy = (byte[])bytes.Clone();
            BitConverter.TryWriteBytes(copy.AsSpan(radii + 16), bad);
            BinaryPrimitives.WriteUInt32LittleEndian(copy.AsSpan(copy.Length - 4), Crc32.Compute(copy.AsSpan(0, copy.Length - 4)));
            var e = Assert.Throws<InvalidDataException>(() => SimulationSnapshot.ReadFrom(new MemoryStream(copy)));
            Assert.Contains("Particle 2's radius", e.Message, StringComparison.Ordinal);
        }
    }

    private static ParticleWorld ClothSystem() => new ClothBuilder { Rows = 3, Columns = 4, Spacing = 0.1 }.Build().System;

    /// <summary>The version 1 bytes of a system: the version 2 layout without the radii, version field 1, checksum redone.</summary>
    private static byte[] VersionOne(ParticleWorld system)
    {
        var stream = new MemoryStream();
        SimulationSnapshot.Capture(system).WriteTo(stream);
        var v2 = stream.ToArray();
        var radii = 28 + (57 * system.Count);
        var v1 = new byte[v2.Length - (8 * system.Count)];
        Array.Copy(v2, v1, radii);
        Array.Copy(v2, radii + (8 * system.Count), v1, radii, v2.Length - radii - (8 * system.Count));
        BinaryPrimitives.WriteUInt16LittleEndian(v1.AsSpan(4), 1);
        BinaryPrimitives.WriteUInt32LittleEndian(v1.AsSpan(v1.Length - 4), Crc32.Compute(v1.AsSpan(0, v1.Length - 4)));
        return v1;
    }
}
