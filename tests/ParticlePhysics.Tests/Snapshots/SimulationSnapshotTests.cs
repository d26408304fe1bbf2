using System;
using System.IO;
using System.Linq;
using System.Text;
using ParticlePhysics.Cloth;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Snapshots;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Snapshots;

/// <summary>Snapshots: bit-exact round trips in memory and on streams, and every kind of bad stream refused.</summary>
[Collection(AllocationMeasurements.Name)]
public class SimulationSnapshotTests
{
    [Fact]
    public void Crc32_matches_the_standard_check_value()
    {
        Assert.Equal(0xCBF43926u, Crc32.Compute(Encoding.ASCII.GetBytes("123456789")));
        Assert.Equal(0u, Crc32.Compute(ReadOnlySpan<byte>.Empty));
    }

    [Theory]
    [InlineData("rk4")]
    [InlineData("rk45")]
    [InlineData("velocity-verlet")]
    [InlineData("implicit-euler")] // its warm start (the last dv) travels in the snapshot
    public void Running_on_after_a_restore_matches_running_on_without_it(string integrator)
    {
        // The original run: 100 steps, a snapshot (saved to a stream), 100 more steps.
        var original = ClothSystem();
        var method = IntegratorCatalog.Create(integrator);
        StateMetrics.Run(original, method, 0.002, 100);
        var saved = new MemoryStream();
        SimulationSnapshot.Capture(original, method).WriteTo(saved);
        var atSnapshot = StateMetrics.BitHash(original.State);
        StateMetrics.Run(original, method, 0.002, 100);

        // A new game: the same scene, a fresh integrator, restored from the stream.
        var restored = ClothSystem();
        var fresh = IntegratorCatalog.Create(integrator);
        saved.Position = 0;
        SimulationSnapshot.ReadFrom(saved).RestoreTo(restored, fresh);
        Assert.Equal(atSnapshot, StateMetrics.BitHash(restored.State));
        Assert.Equal(100 * 0.002, restored.Time, 12);
        StateMetrics.Run(restored, fresh, 0.002, 100);
        Assert.Equal(StateMetrics.BitHash(original.State), StateMetrics.BitHash(restored.State));
        Assert.Equal(original.Time, restored.Time);
    }

    [Fact]
    public void An_implicit_euler_state_that_it_could_not_have_written_is_refused_and_changes_nothing()
    {
        var implicitEuler = new ImplicitEuler();
        var system = ClothSystem();
        implicitEuler.ReadState(new double[] { 0 });
        Assert.Equal(1, implicitEuler.StateLength);
        Assert.Throws<ArgumentException>("source", () => implicitEuler.ReadState(new double[] { 1, 0.5 }));
        Assert.Throws<ArgumentException>("source", () => implicitEuler.ReadState(new double[] { 1, 0, 0, double.NaN }));
        Assert.Throws<ArgumentException>("source", () => implicitEuler.ReadState(new double[] { 2 }));
        Assert.Equal(1, implicitEuler.StateLength);
        StateMetrics.Run(system, implicitEuler, 1.0 / 60, 1);
        Assert.Equal(1 + system.CoordinateCount, implicitEuler.StateLength);       // the last dv
        StateMetrics.Run(system, implicitEuler, 1.0 / 60, 1);
        Assert.Equal(1 + (2 * system.CoordinateCount), implicitEuler.StateLength); // and the one before
        Assert.Throws<ArgumentException>("source", () => implicitEuler.ReadState(new double[] { 2, 1, 2, 3 }));
    }

    [Fact]
    public void Under_the_multigrid_the_warm_starts_products_are_part_of_the_state_and_the_older_format_still_reads()
    {
        // The 16 x 16 cloth: 256 particles, so implicit Euler's multigrid preconditioner, whose warm start keeps the
        // last four steps' dv and their products A dv: the header counts both, k + 3 p while k <= 2 (the format of the
        // library that kept two steps) and 16 + k + 8 p beyond.
        var n = new ClothScenario { Resolution = 1.0 / 15 }.Build().CoordinateCount;
        var original = new ClothScenario { Resolution = 1.0 / 15 }.Build();
        var implicitEuler = new ImplicitEuler { Tolerance = 1e-3 };
        StateMetrics.Run(original, implicitEuler, 1.0 / 60, 1);
        Assert.Equal(1 + (2 * n), implicitEuler.StateLength);
        Assert.Equal(4.0, Written(implicitEuler)[0]); // one step known, with its product
        StateMetrics.Run(original, implicitEuler, 1.0 / 60, 1);
        Assert.Equal(8.0, Written(implicitEuler)[0]); // two steps, both products: as the older library wrote it
        var twoSteps = Written(implicitEuler);
        StateMetrics.Run(original, implicitEuler, 1.0 / 60, 1);
        Assert.Equal(16.0 + 3 + 24, Written(implicitEuler)[0]); // three
        StateMetrics.Run(original, implicitEuler, 1.0 / 60, 2);
        Assert.Equal(1 + (8 * n), implicitEuler.StateLength);
        var state = Written(implicitEuler);
        Assert.Equal(16.0 + 4 + 32, state[0]); // four steps, four products: the most it keeps
        Assert.True(SimulationSnapshot.MaxIntegratorStateLength(n / 3) >= state.Length);

        // Restored from the full state, a run continues bit for bit.
        var atSave = original.State.ToArray();
        var time = original.Time;
        StateMetrics.Run(original, implicitEuler, 1.0 / 60, 3);
        var restored = new ClothScenario { Resolution = 1.0 / 15 }.Build();
        restored.SetState(atSave);
        restored.Time = time;
        var fresh = new ImplicitEuler { Tolerance = 1e-3 };
        fresh.ReadState(state);
        StateMetrics.Run(restored, fresh, 1.0 / 60, 3);
        Assert.Equal(StateMetrics.BitHash(original.State), StateMetrics.BitHash(restored.State));

        // The older formats: two steps with their products (header 8) start from those two, then the history grows
        // again; the two dv alone (header 2, before products were kept) start from their extrapolation.
        var fromTwo = new ImplicitEuler { Tolerance = 1e-3 };
        fromTwo.ReadState(twoSteps);
        Assert.Equal(twoSteps.Length, fromTwo.StateLength);
        restored.SetState(atSave);
        restored.Time = time;
        StateMetrics.Run(restored, fromTwo, 1.0 / 60, 1);
        Assert.Equal(16.0 + 3 + 24, Written(fromTwo)[0]);
        var older = new ImplicitEuler { Tolerance = 1e-3 };
        older.ReadState(state.AsSpan(0, 1 + (2 * n)).ToArray().Select((v, i) => i == 0 ? 2.0 : v).ToArray());
        Assert.Equal(1 + (2 * n), older.StateLength);
        restored.SetState(atSave);
        restored.Time = time;
        StateMetrics.Run(restored, older, 1.0 / 60, 1);
        Assert.Equal(16.0 + 3 + 8, Written(older)[0]); // three steps known, the last one's product
        StateMetrics.Run(restored, older, 1.0 / 60, 1);
        Assert.Equal(16.0 + 4 + 16, Written(older)[0]);

        // Headers that no state has: p > k, k beyond 4, k <= 2 in the deep form, not whole, or not a whole number of
        // vectors after them.
        foreach (var header in new[] { 3.0, 6.0, 7.0, 9.0, -1.0, 16.0, 18.0, 16.0 + 5, 16.0 + 3 + 32, 16.0 + 4 + 40, 20.5 })
        {
            Assert.Throws<ArgumentException>("source", () => fresh.ReadState(new[] { header }.Concat(new double[2 * n]).ToArray()));
        }

        Assert.Throws<ArgumentException>("source", () => fresh.ReadState(new[] { 8.0 }.Concat(new double[(4 * n) - 3]).ToArray()));
        Assert.Throws<ArgumentException>("source", () => fresh.ReadState(new[] { 16.0 + 4 + 32 }.Concat(new double[(8 * n) - 3]).ToArray()));
    }

    [Fact]
    public void The_adaptive_integrators_step_size_is_part_of_the_state()
    {
        var system = ClothSystem();
        var rk45 = new DormandPrince45();
        StateMetrics.Run(system, rk45, 0.01, 5);
        var snapshot = SimulationSnapshot.Capture(system, rk45);
        Assert.Equal("rk45", snapshot.IntegratorName);
        Assert.Equal(rk45.CurrentStepSize, snapshot.IntegratorState[0]);

        var restored = new DormandPrince45();
        snapshot.RestoreTo(ClothSystem(), restored);
        Assert.Equal(rk45.CurrentStepSize, restored.CurrentStepSize);
    }

    [Fact]
    public void A_round_trip_through_a_stream_is_bit_exact_for_time_state_masses_pins_and_integrator()
    {
        var system = ClothSystem();
        StateMetrics.Run(system, new RungeKutta4(), 0.001, 30);
        system.Unpin(0);
        system.Pin(7);
        system.SetMass(3, 0.125);
        system.SetVelocity(6, new Vector3d(double.Epsilon, -0.0, 1e300));
        var rk45 = new DormandPrince45 { CurrentStepSize = 1.0 / 3 };
        var snapshot = SimulationSnapshot.Capture(system, rk45);
        var stream = new MemoryStream();
        snapshot.WriteTo(stream);
        Assert.Equal(snapshot.SerializedLength, stream.Length);

        stream.Position = 0;
        var read = SimulationSnapshot.ReadFrom(stream);
        Assert.Equal(BitConverter.DoubleToInt64Bits(system.Time), BitConverter.DoubleToInt64Bits(read.Time));
        Assert.Equal(StateMetrics.BitHash(snapshot.State), StateMetrics.BitHash(read.State));
        Assert.Equal(StateMetrics.BitHash(snapshot.Masses), StateMetrics.BitHash(read.Masses));
        Assert.True(snapshot.Pinned.SequenceEqual(read.Pinned));
        Assert.Equal("rk45", read.IntegratorName);
        Assert.Equal(1.0 / 3, read.IntegratorState[0]);

        // Into a freshly built cloth (pinned at its corners, other masses): everything comes back.
        var target = ClothSystem();
        read.RestoreTo(target);
        Assert.Equal(StateMetrics.BitHash(system.State), StateMetrics.BitHash(target.State));
        Assert.False(target.IsPinned(0));
        Assert.True(target.IsPinned(7));
        Assert.Equal(0.125, target.GetMass(3));
        Assert.Equal(system.Time, target.Time);
    }

    [Fact]
    public void Snapshots_follow_one_another_in_a_stream()
    {
        var system = ClothSystem();
        var stream = new MemoryStream();
        SimulationSnapshot.Capture(system).WriteTo(stream);
        StateMetrics.Run(system, new RungeKutta4(), 0.001, 10);
        SimulationSnapshot.Capture(system).WriteTo(stream);
        stream.Position = 0;
        Assert.Equal(0.0, SimulationSnapshot.ReadFrom(stream).Time);
        Assert.Equal(system.Time, SimulationSnapshot.ReadFrom(stream).Time);
        Assert.Equal(stream.Length, stream.Position);
    }

    [Fact]
    public void Capturing_and_restoring_in_memory_allocate_nothing()
    {
        var system = ClothSystem();
        var rk45 = new DormandPrince45();
        var snapshot = SimulationSnapshot.Capture(system, rk45);
        snapshot.RestoreTo(system, rk45);
        Assert.Equal(0, ThreadAllocations.Measure(() =>
        {
            for (var i = 0; i < 20; i++)
            {
                snapshot.CaptureFrom(system, rk45);
                snapshot.RestoreTo(system, rk45);
            }
        }));
    }

    [Theory]
    [InlineData(0)]
    [InlineData(3)]
    [InlineData(27)]
    [InlineData(28)]
    [InlineData(40)]
    [InlineData(200)]
    [InlineData(-1)]
    public void A_truncated_stream_is_refused(int length)
    {
        var bytes = Serialized(ClothSystem(), new DormandPrince45());
        var cut = length < 0 ? bytes.Length + length : length;
        foreach (var seekable in new[] { true, false })
        {
            Stream stream = seekable ? new MemoryStream(bytes, 0, cut) : new ForwardOnlyStream(bytes, cut);
            var e = Assert.Throws<InvalidDataException>(() => SimulationSnapshot.ReadFrom(stream));
            Assert.Contains("truncated", e.Message, StringComparison.Ordinal);
        }
    }

    [Fact]
    public void Every_flipped_byte_is_refused()
    {
        var bytes = Serialized(new ClothBuilder { Rows = 2, Columns = 2 }.Build().System, new DormandPrince45());
        for (var i = 0; i < bytes.Length; i++)
        {
            for (var bit = 0; bit < 8; bit += 7)
            {
                var damaged = (byte[])bytes.Clone();
                damaged[i] ^= (byte)(1 << bit);
                Assert.Throws<InvalidDataException>(() => SimulationSnapshot.ReadFrom(new MemoryStream(damaged)));
            }
        }
    }

    [Fact]
    public void A_payload_byte_flipped_is_reported_as_a_checksum_mismatch()
    {
        var bytes = Serialized(ClothSystem(), null);
        bytes[100] ^= 0x10;
        var e = Assert.Throws<InvalidDataException>(() => SimulationSnapshot.ReadFrom(new MemoryStream(bytes)));
        Assert.Contains("CRC-32", e.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Wrong_magic_future_version_and_impossible_counts_are_named()
    {
        var bytes = Serialized(ClothSystem(), null);
        AssertInvalid(WithCrc(bytes, b => b[0] = (byte)'X'), "PPSN");
        AssertInvalid(WithCrc(bytes, b => b[4] = 3), "version 3, newer");
        AssertInvalid(WithCrc(bytes, b => b[4] = 0), "version 0");
        AssertInvalid(WithCrc(bytes, b => b[11] = 0x80), "particle count -");
        AssertInvalid(WithCrc(bytes, b => b[8]++), "truncated");
        AssertInvalid(WithCrc(bytes, b => b[8]--), "CRC-32");
        AssertInvalid(WithCrc(bytes, b => b[19] = 0x7F), "integrator state length");
    }

    [Fact]
    public void Values_no_system_can_hold_are_refused_even_with_a_valid_checksum()
    {
        var system = ClothSystem();
        var bytes = Serialized(system, null);
        var n = system.Count;
        var masses = 28 + (48 * n);
        AssertInvalid(WithCrc(bytes, b => BitConverter.TryWriteBytes(b.AsSpan(masses + 8), -1.0)), "Particle 1's mass");
        AssertInvalid(WithCrc(bytes, b => BitConverter.TryWriteBytes(b.AsSpan(28 + 24), double.NaN)), "Particle 1's position");
        AssertInvalid(WithCrc(bytes, b => BitConverter.TryWriteBytes(b.AsSpan(20), double.PositiveInfinity)), "time");
        AssertInvalid(WithCrc(bytes, b => b[masses + (8 * n) + 2] = 2), "pinned flag");
    }

    [Fact]
    public void A_pinned_particle_moving_at_a_velocity_comes_back_moving()
    {
        // A kinematic anchor the host drives has a velocity: the snapshot keeps it, and the restored run goes on alike.
        var source = ClothSystem();
        source.SetVelocity(0, new Vector3d(0.5, 0, -0.25));
        StateMetrics.Run(source, new RungeKutta4(), 0.001, 10);
        var read = SimulationSnapshot.ReadFrom(new MemoryStream(Serialized(source, null)));
        var target = ClothSystem();
        read.RestoreTo(target);
        Assert.Equal(new Vector3d(0.5, 0, -0.25), target.GetVelocity(0));
        Assert.True(target.IsPinned(0));
        StateMetrics.Run(source, new RungeKutta4(), 0.001, 10);
        StateMetrics.Run(target, new RungeKutta4(), 0.001, 10);
        Assert.Equal(StateMetrics.BitHash(source.State), StateMetrics.BitHash(target.State));
    }

    [Fact]
    public void A_snapshot_refuses_a_system_or_integrator_that_does_not_match_and_changes_nothing()
    {
        var source = ClothSystem();
        StateMetrics.Run(source, new RungeKutta4(), 0.001, 10);
        var snapshot = SimulationSnapshot.Capture(source, new RungeKutta4());
        var target = ClothSystem();
        StateMetrics.Run(target, new RungeKutta4(), 0.001, 3);
        var hash = StateMetrics.BitHash(target.State);

        var smaller = new ClothBuilder { Rows = 3, Columns = 3 }.Build().System;
        var e = Assert.Throws<ArgumentException>(() => snapshot.RestoreTo(smaller));
        Assert.Equal("system", e.ParamName);
        Assert.Contains($"{source.Count} particles but the system has 9", e.Message, StringComparison.Ordinal);
        Assert.Equal("integrator", Assert.Throws<ArgumentException>(() => snapshot.RestoreTo(target, new ExplicitEuler())).ParamName);
        Assert.Equal(
            "integrator",
            Assert.Throws<ArgumentException>(() => SimulationSnapshot.Capture(source).RestoreTo(target, new DormandPrince45())).ParamName);

        // A bad integrator value from a stream is refused by the integrator before the particles are touched.
        var rk45 = new DormandPrince45 { CurrentStepSize = 0.5 };
        var bytes = Serialized(source, rk45);
        var damaged = WithCrc(bytes, b => BitConverter.TryWriteBytes(b.AsSpan(b.Length - 12), double.NaN));
        var read = SimulationSnapshot.ReadFrom(new MemoryStream(damaged));
        Assert.Throws<ArgumentOutOfRangeException>(() => read.RestoreTo(target, rk45));
        Assert.Equal(0.5, rk45.CurrentStepSize);

        Assert.Equal(hash, StateMetrics.BitHash(target.State));
        Assert.Equal(3 * 0.001, target.Time, 15);
        Assert.True(target.IsPinned(0));
    }

    [Fact]
    public void A_header_that_announces_millions_of_particles_on_a_stream_that_ends_allocates_kilobytes_not_what_it_announced()
    {
        // Issue 10, item 8: 28 bytes announcing 4,194,304 particles made ReadFrom allocate 440 MB on a non-seekable
        // stream before it reported the truncation.
        var header = new byte[28];
        Encoding.ASCII.GetBytes("PPSN").CopyTo(header, 0);
        header[4] = SimulationSnapshot.FormatVersion;
        BitConverter.TryWriteBytes(header.AsSpan(8), ParticleWorld.MaxParticles);
        _ = Assert.Throws<InvalidDataException>(() => SimulationSnapshot.ReadFrom(new ForwardOnlyStream(header, 28))); // warm-up: JIT
        var before = GC.GetAllocatedBytesForCurrentThread();
        var e = Assert.Throws<InvalidDataException>(() => SimulationSnapshot.ReadFrom(new ForwardOnlyStream(header, 28)));
        var allocated = GC.GetAllocatedBytesForCurrentThread() - before;
        Assert.Contains("truncated", e.Message, StringComparison.Ordinal);
        Assert.True(allocated < 256 * 1024, $"allocated {allocated} bytes for a 28-byte stream");

        // Still bounded by what arrives: a megabyte of a 440 MB announcement costs a few megabytes at most.
        var partial = new byte[1 << 20];
        header.CopyTo(partial, 0);
        before = GC.GetAllocatedBytesForCurrentThread();
        Assert.Throws<InvalidDataException>(() => SimulationSnapshot.ReadFrom(new ForwardOnlyStream(partial, partial.Length)));
        allocated = GC.GetAllocatedBytesForCurrentThread() - before;
        Assert.True(allocated < 4 * partial.Length, $"allocated {allocated} bytes for a {partial.Length}-byte stream");
    }

    [Fact]
    public void A_mass_whose_inverse_overflows_is_refused_when_read()
    {
        var system = ClothSystem();
        var bytes = Serialized(system, null);
        var masses = 28 + (48 * system.Count);
        AssertInvalid(WithCrc(bytes, b => BitConverter.TryWriteBytes(b.AsSpan(masses + 8), 1e-320)), "Particle 1's mass");
    }

    private static double[] Written(ImplicitEuler integrator)
    {
        var state = new double[integrator.StateLength];
        integrator.WriteState(state);
        return state;
    }

    private static ParticleWorld ClothSystem() => new ClothBuilder { Rows = 4, Columns = 5, Spacing = 0.1 }.Build().System;

    private static byte[] Serialized(ParticleWorld system, IIntegrator? integrator)
    {
        var stream = new MemoryStream();
        SimulationSnapshot.Capture(system, integrator).WriteTo(stream);
        return stream.ToArray();
    }

    /// <summary>A copy with <paramref name="edit"/> applied and the checksum recomputed, to reach the checks after it.</summary>
    private static byte[] WithCrc(byte[] bytes, Action<byte[]> edit)
    {
        var copy = (byte[])bytes.Clone();
        edit(copy);
        BitConverter.TryWriteBytes(copy.AsSpan(copy.Length - 4), Crc32.Compute(copy.AsSpan(0, copy.Length - 4)));
        return copy;
    }

    private static void AssertInvalid(byte[] bytes, string expected)
    {
        var e = Assert.Throws<InvalidDataException>(() => SimulationSnapshot.ReadFrom(new MemoryStream(bytes)));
        Assert.Contains(expected, e.Message, StringComparison.Ordinal);
    }
}
