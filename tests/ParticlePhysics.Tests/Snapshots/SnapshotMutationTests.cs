using System;
using System.Buffers.Binary;
using System.IO;
using ParticlePhysics.Contacts;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Snapshots;
using ParticlePhysics.Tests.Support;
using Xunit.Abstractions;

namespace ParticlePhysics.Tests.Snapshots;

/// <summary>
/// Issue 10: a snapshot stream mutated in every way (every bit flipped, truncated at every length, bytes appended,
/// edits with a valid checksum, random multi-byte damage) is either rejected with InvalidDataException and nothing
/// changed, or accepted and consistent (it restores into a world as a whole or not at all, the world then holds only
/// what a world may hold, and it writes back to the bytes it was read from). None throws anything else, hangs, or
/// allocates more than a small multiple of what the stream delivered.
/// </summary>
[Collection(AllocationMeasurements.Name)]
public class SnapshotMutationTests
{
    private readonly ITestOutputHelper _output;

    public SnapshotMutationTests(ITestOutputHelper output)
    {
        _output = output;
    }

    /// <summary>Each integrator's snapshot in the current format (2, with radii) and in format 1 (without), which is still read.</summary>
    public static TheoryData<string, int> Integrators() => new()
    {
        { "implicit-euler", 2 }, { "rk45", 2 }, { "rk4", 2 }, { "implicit-euler", 1 }, { "rk45", 1 }, { "rk4", 1 },
    };

    [Theory]
    [MemberData(nameof(Integrators))]
    public void Every_flipped_bit_is_rejected(string integrator, int version)
    {
        var bytes = Serialized(integrator, version);
        for (var i = 0; i < bytes.Length; i++)
        {
            for (var bit = 0; bit < 8; bit++)
            {
                var damaged = (byte[])bytes.Clone();
                damaged[i] ^= (byte)(1 << bit);
                var outcome = Read(damaged, seekable: bit % 2 == 0);
                Assert.True(outcome is InvalidDataException, $"byte {i} bit {bit}: {outcome}");
            }
        }
    }

    [Theory]
    [MemberData(nameof(Integrators))]
    public void A_stream_cut_at_every_length_is_rejected_as_truncated(string integrator, int version)
    {
        var bytes = Serialized(integrator, version);
        for (var length = 0; length < bytes.Length; length++)
        {
            foreach (var seekable in new[] { true, false })
            {
                var outcome = Read(bytes.AsSpan(0, length).ToArray(), seekable);
                Assert.True(
                    outcome is InvalidDataException e && e.Message.Contains("truncated", StringComparison.Ordinal),
                    $"cut at {length} of {bytes.Length} ({(seekable ? "seekable" : "forward only")}): {outcome}");
            }
        }
    }

    [Theory]
    [MemberData(nameof(Integrators))]
    public void Bytes_appended_after_a_snapshot_are_left_in_the_stream(string integrator, int version)
    {
        var bytes = Serialized(integrator, version);
        var random = new SeededRandom(11);
        foreach (var extra in new[] { 1, 3, 28, 1000 })
        {
            var stream = new MemoryStream();
            stream.Write(bytes);
            for (var i = 0; i < extra; i++)
            {
                stream.WriteByte((byte)random.Next(256));
            }

            stream.Position = 0;
            var snapshot = SimulationSnapshot.ReadFrom(stream);
            Assert.Equal(bytes.Length, stream.Position);
            Assert.Equal(version == 2 ? bytes : Serialized(integrator, 2, radii: false), Written(snapshot));
        }
    }

    [Theory]
    [MemberData(nameof(Integrators))]
    public void Every_byte_edited_with_a_valid_checksum_is_rejected_or_accepted_and_consistent(string integrator, int version)
    {
        var bytes = Serialized(integrator, version);
        var random = new SeededRandom(23);
        var accepted = 0;
        for (var i = 0; i < bytes.Length - 4; i++)
        {
            foreach (var value in new[] { (byte)(bytes[i] ^ 0xFF), (byte)0, (byte)0x7F, (byte)random.Next(256) })
            {
                if (value == bytes[i])
                {
                    continue;
                }

                var edited = WithCrc(bytes, b => b[i] = value);
                accepted += Check(edited, integrator, version, $"byte {i} set to 0x{value:X2}") ? 1 : 0;
            }
        }

        // Some edits must get through the checks (a mass, a coordinate, the time): those are the ones to follow further.
        _output.WriteLine($"{integrator}: {accepted} of the single-byte edits with a valid checksum accepted, the rest rejected");
        Assert.True(accepted > 50, $"only {accepted} edits were accepted");
    }

    [Theory]
    [MemberData(nameof(Integrators))]
    public void Thousands_of_random_multi_byte_mutations_are_rejected_or_accepted_and_consistent(string integrator, int version)
    {
        var bytes = Serialized(integrator, version);
        var random = new SeededRandom(5000 + (ulong)integrator.Length);
        var accepted = 0;
        for (var m = 0; m < 2000; m++)
        {
            var edited = (byte[])bytes.Clone();
            var edits = random.Next(1, 5);
            for (var e = 0; e < edits; e++)
            {
                edited[random.Next(edited.Length)] = (byte)random.Next(256);
            }

            if (random.Chance(0.2))
            {
                Array.Resize(ref edited, Math.Max(0, edited.Length + random.Next(-8, 9)));
            }

            if (random.Chance(0.7) && edited.Length >= 4)
            {
                edited = WithCrc(edited, _ => { });
            }

            accepted += Check(edited, integrator, version, $"mutation {m}") ? 1 : 0;
        }

        _output.WriteLine($"{integrator}: 2000 random mutations, {accepted} accepted and consistent, {2000 - accepted} rejected");
    }

    [Fact]
    public void Headers_that_announce_huge_counts_cost_what_the_stream_holds_not_what_they_announce()
    {
        var bytes = Serialized("rk45");
        foreach (var (offset, value) in new[] { (8, ParticleWorld.MaxParticles), (8, 4_000_000), (16, 1024 + (6 * 3)), (12, 256) })
        {
            var edited = WithCrc(bytes, b => BitConverter.TryWriteBytes(b.AsSpan(offset), value));
            var before = GC.GetAllocatedBytesForCurrentThread();
            var outcome = Read(edited, seekable: false);
            var allocated = GC.GetAllocatedBytesForCurrentThread() - before;
            Assert.IsType<InvalidDataException>(outcome);
            Assert.True(allocated < 256 * 1024, $"field at {offset} = {value}: {allocated} bytes allocated for {edited.Length}");
        }
    }

    /// <summary>
    /// Reads <paramref name="bytes"/>; when accepted, restores it into a world built like the original and checks the
    /// world. Returns whether the snapshot was accepted.
    /// </summary>
    private static bool Check(byte[] bytes, string integrator, int version, string what)
    {
        var before = GC.GetAllocatedBytesForCurrentThread();
        SimulationSnapshot? snapshot = null;
        Exception? failure = null;
        try
        {
            snapshot = SimulationSnapshot.ReadFrom(new ForwardOnlyStream(bytes, bytes.Length));
        }
        catch (Exception e)
        {
            failure = e;
        }

        var allocated = GC.GetAllocatedBytesForCurrentThread() - before;
        Assert.True(allocated < (16L * bytes.Length) + (128 * 1024), $"{what}: {allocated} bytes allocated to read {bytes.Length}");
        if (failure is not null)
        {
            Assert.True(failure is InvalidDataException, $"{what}: {failure}");
            return false;
        }

        // Accepted: it writes back to the same bytes (a format 1 stream: to the same values in format 2, radius 0), and
        // restores into a world whole or not at all.
        if (version == 2)
        {
            Assert.Equal(bytes.AsSpan(0, snapshot!.SerializedLength).ToArray(), Written(snapshot));
        }
        else
        {
            Assert.All(snapshot!.Radii.ToArray(), r => Assert.Equal(0.0, r));
            Assert.Equal(Written(snapshot), Written(SimulationSnapshot.ReadFrom(new MemoryStream(Written(snapshot)))));
        }

        var world = World();
        var method = IntegratorCatalog.Create(integrator);
        world.Step(method, 0.01);
        var observed = Observe(world, method);
        try
        {
            snapshot.RestoreTo(world, method);
        }
        catch (ArgumentException)
        {
            Assert.True(observed == Observe(world, method), $"{what}: a refused restore changed the world");
            return true;
        }

        for (var i = 0; i < world.Count; i++)
        {
            var m = world.Masses[i];
            Assert.True(m > 0 && double.IsFinite(m) && double.IsFinite(1 / m), $"{what}: mass {m}");
            Assert.Equal(world.IsPinned(i) ? 0 : 1 / m, world.InverseMasses[i]);
        }

        Assert.All(world.State.ToArray(), v => Assert.True(double.IsFinite(v), $"{what}: a state value {v}"));
        Assert.True(double.IsFinite(world.Time), what);

        // And it steps, or fails a step as a whole.
        observed = Observe(world, method);
        try
        {
            world.Step(method, 0.01);
        }
        catch (Exception e) when (e is SimulationDivergedException or SolverNotConvergedException or ArgumentException)
        {
            Assert.True(observed == Observe(world, method), $"{what}: a failed step changed the world");
        }

        return true;
    }

    private static Exception? Read(byte[] bytes, bool seekable)
    {
        try
        {
            Stream stream = seekable ? new MemoryStream(bytes) : new ForwardOnlyStream(bytes, bytes.Length);
            _ = SimulationSnapshot.ReadFrom(stream);
            return null;
        }
        catch (Exception e)
        {
            return e;
        }
    }

    /// <summary>Three particles (one pinned) on springs under gravity, with some history, so every field has content.</summary>
    private static ParticleWorld World()
    {
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(0, 0, 0), 1);
        world.AddParticle(new Vector3d(0.5, -0.2, 0.1), new Vector3d(0.1, 0, 0), 0.5);
        world.AddParticle(new Vector3d(1, -0.4, 0), 0.7);
        world.Pin(0);
        var springs = new SpringNetwork(world);
        springs.Add(0, 1, 20, 0.5, 0.1);
        springs.Add(1, 2, 20, 0.5, 0.1);
        world.AddForce(springs);
        world.AddForce(new Gravity());

        // Radii (format 2) that the contact stage reads: the lowest particle reaches the ground within a few steps.
        world.SetRadius(0, 0.05);
        world.SetRadius(1, 0.1);
        world.SetRadius(2, 0.02);
        var contacts = new ContactSet { ParticleCollisions = true };
        contacts.Add(new PlaneObstacle(new Vector3d(0, -0.45, 0), new Vector3d(0, 1, 0), 0.5, 0.2));
        world.AddConstraints(contacts);
        return world;
    }

    /// <summary>The snapshot's bytes in format <paramref name="version"/> (1: the format 2 layout without the radii).</summary>
    private static byte[] Serialized(string integrator, int version = 2, bool radii = true)
    {
        var world = World();
        if (!radii)
        {
            for (var i = 0; i < world.Count; i++)
            {
                world.SetRadius(i, 0);
            }
        }

        var method = IntegratorCatalog.Create(integrator);
        StateMetrics.Run(world, method, 0.01, 5); // implicit Euler's warm start holds two steps
        var stream = new MemoryStream();
        SimulationSnapshot.Capture(world, method).WriteTo(stream);
        var v2 = stream.ToArray();
        if (version == 2)
        {
            return v2;
        }

        var n = world.Count;
        var at = 28 + BinaryPrimitives.ReadInt32LittleEndian(v2.AsSpan(12)) + (57 * n);
        var v1 = new byte[v2.Length - (8 * n)];
        Array.Copy(v2, v1, at);
        Array.Copy(v2, at + (8 * n), v1, at, v2.Length - at - (8 * n));
        BinaryPrimitives.WriteUInt16LittleEndian(v1.AsSpan(4), 1);
        BinaryPrimitives.WriteUInt32LittleEndian(v1.AsSpan(v1.Length - 4), Crc32.Compute(v1.AsSpan(0, v1.Length - 4)));
        return v1;
    }

    private static byte[] Written(SimulationSnapshot snapshot)
    {
        var stream = new MemoryStream();
        snapshot.WriteTo(stream);
        return stream.ToArray();
    }

    private static string Observe(ParticleWorld world, IIntegrator integrator)
    {
        var state = integrator is IStatefulIntegrator stateful ? new double[stateful.StateLength] : Array.Empty<double>();
        (integrator as IStatefulIntegrator)?.WriteState(state);
        var pins = new double[world.Count];
        for (var i = 0; i < world.Count; i++)
        {
            pins[i] = world.IsPinned(i) ? 1 : 0;
        }

        return string.Join(
            "|",
            StateMetrics.BitHash(world.State),
            StateMetrics.BitHash(world.Masses),
            StateMetrics.BitHash(world.InverseMasses),
            StateMetrics.BitHash(pins),
            StateMetrics.BitHash(new[] { world.Time }),
            StateMetrics.BitHash(world.Radii),
            StateMetrics.BitHash(state));
    }

    private static byte[] WithCrc(byte[] bytes, Action<byte[]> edit)
    {
        var copy = (byte[])bytes.Clone();
        edit(copy);
        BitConverter.TryWriteBytes(copy.AsSpan(copy.Length - 4), Crc32.Compute(copy.AsSpan(0, copy.Length - 4)));
        return copy;
    }
}
