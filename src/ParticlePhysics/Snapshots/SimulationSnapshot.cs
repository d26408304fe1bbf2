using System;
using System.Buffers.Binary;
using System.IO;
using System.Text;
using ParticlePhysics.Integrators;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Snapshots;

/// <summary>
/// The whole dynamic state of a <see cref="ParticleWorld"/> (time, positions, velocities, masses, pins, radii) and of its
/// integrator (<see cref="IStatefulIntegrator"/>), captured and restored bit for bit: for save games, replays and
/// rollback. It does not hold the force generators: they are the scene's configuration, which the host rebuilds (the
/// same builder code) before restoring.
/// </summary>
/// <remarks>
/// In memory, <see cref="CaptureFrom"/> and <see cref="RestoreTo"/> reuse the snapshot's arrays, so a rollback buffer of
/// snapshots allocates nothing per frame. On a stream, <see cref="WriteTo"/> and <see cref="ReadFrom"/> use a
/// versioned binary format, all little-endian:
/// <code>
/// offset  size  field
///  0       4    magic "PPSN"
///  4       2    format version (2; version 1, without radii, is still read: its particles get radius 0)
///  6       2    flags (0)
///  8       4    particle count n
/// 12       4    integrator name length b, in UTF-8 bytes (0: captured without an integrator)
/// 16       4    integrator state length m, in doubles
/// 20       8    time
/// 28       b    integrator name (UTF-8)
///          48 n state vector [positions | velocities], 6 doubles per particle
///          8 n  masses
///          n    pinned flags (0 or 1)
///          8 n  radii (version 2 on)
///          8 m  integrator state
///          4    CRC-32 of every byte before it
/// </code>
/// Reading checks everything (magic, version, counts, length, checksum, then every value) before it returns, and
/// <see cref="RestoreTo"/> checks the snapshot against the system before it writes: a bad stream or a mismatched
/// system throws and leaves the live system untouched.
/// </remarks>
public sealed class SimulationSnapshot
{
    /// <summary>The format version that <see cref="WriteTo"/> writes and <see cref="ReadFrom"/> reads.</summary>
    public const int FormatVersion = 2;

    /// <summary>The oldest format version that <see cref="ReadFrom"/> still reads (1: without radii).</summary>
    public const int OldestReadableVersion = 1;

    /// <summary>
    /// The largest integrator state, in doubles, that the format accepts for <paramref name="particleCount"/>
    /// particles: <see cref="IntegratorStateLimit.MaxLength"/>, 1024 plus 24 per particle (implicit Euler's warm
    /// start is up to eight vectors over the particles: the last four steps' velocity changes and their products).
    /// </summary>
    public static int MaxIntegratorStateLength(int particleCount) => IntegratorStateLimit.MaxLength(particleCount);

    /// <summary>The largest integrator name, in UTF-8 bytes, that the binary format accepts.</summary>
    public const int MaxIntegratorNameLength = 256;

    private const int HeaderSize = 28;
    private const int ReadChunk = 64 * 1024;
    private const int ChecksumSize = 4;
    private static readonly byte[] _magic = { (byte)'P', (byte)'P', (byte)'S', (byte)'N' };

    private double[] _state = Array.Empty<double>();
    private double[] _masses = Array.Empty<double>();
    private bool[] _pinned = Array.Empty<bool>();
    private double[] _radii = Array.Empty<double>();
    private double[] _integratorState = Array.Empty<double>();

    private SimulationSnapshot()
    {
    }

    /// <summary>The number of particles.</summary>
    public int ParticleCount => _masses.Length;

    /// <summary>The simulated time, in seconds.</summary>
    public double Time { get; private set; }

    /// <summary>The state vector [positions | velocities], 6 values per particle, as <see cref="ParticleWorld.State"/>.</summary>
    public ReadOnlySpan<double> State => _state;

    /// <summary>The masses, one per particle.</summary>
    public ReadOnlySpan<double> Masses => _masses;

    /// <summary>The pinned flags, one per particle.</summary>
    public ReadOnlySpan<bool> Pinned => _pinned;

    /// <summary>The radii, one per particle (0 for a snapshot read from format version 1).</summary>
    public ReadOnlySpan<double> Radii => _radii;

    /// <summary>The <see cref="IIntegrator.Name"/> of the integrator captured with the system, or null.</summary>
    public string? IntegratorName { get; private set; }

    /// <summary>The integrator's state (<see cref="IStatefulIntegrator"/>), empty for a stateless one.</summary>
    public ReadOnlySpan<double> IntegratorState => _integratorState;

    /// <summary>Captures <paramref name="system"/> and, optionally, the integrator that steps it.</summary>
    /// <param name="system">The system.</param>
    /// <param name="integrator">
    /// The integrator, or null: needed for a bit-exact continuation with an integrator that carries state
    /// (<see cref="DormandPrince45"/>); its name is recorded either way and checked on restore.
    /// </param>
    public static SimulationSnapshot Capture(ParticleWorld system, IIntegrator? integrator = null)
    {
        var snapshot = new SimulationSnapshot();
        snapshot.CaptureFrom(system, integrator);
        return snapshot;
    }

    /// <summary>
    /// Overwrites this snapshot with the state of <paramref name="system"/> (and <paramref name="integrator"/>),
    /// reusing its arrays when the sizes match: allocates nothing when capturing the same system again.
    /// </summary>
    public void CaptureFrom(ParticleWorld system, IIntegrator? integrator = null)
    {
        Guard.NotNull(system, nameof(system));
        var n = system.Count;
        var stateful = integrator as IStatefulIntegrator;
        var m = stateful?.StateLength ?? 0;
        if (m < 0 || m > MaxIntegratorStateLength(system.Count))
        {
            throw new ArgumentException(
                $"The integrator's StateLength must be 0 to {MaxIntegratorStateLength(system.Count)}; got {m}.",
                nameof(integrator));
        }

        var name = integrator?.Name;
        if (name is not null && Encoding.UTF8.GetByteCount(name) > MaxIntegratorNameLength)
        {
            throw new ArgumentException(
                $"The integrator's name must be at most {MaxIntegratorNameLength} UTF-8 bytes long.", nameof(integrator));
        }

        var state = Resize(_state, 6 * n);
        var masses = Resize(_masses, n);
        var pinned = _pinned.Length == n ? _pinned : new bool[n];
        var radii = Resize(_radii, n);
        var integratorState = Resize(_integratorState, m);
        stateful?.WriteState(integratorState);
        system.State.CopyTo(state);
        system.Masses.CopyTo(masses);
        system.Radii.CopyTo(radii);
        for (var i = 0; i < n; i++)
        {
            pinned[i] = system.IsPinned(i);
        }

        _state = state;
        _masses = masses;
        _pinned = pinned;
        _radii = radii;
        _integratorState = integratorState;
        IntegratorName = name;
        Time = system.Time;
    }

    /// <summary>
    /// Restores the captured state into <paramref name="system"/> (and <paramref name="integrator"/>), bit for bit.
    /// Everything is checked first; a rejected call throws and changes nothing. Allocates nothing. A
    /// <see cref="Driver.FixedTimestepDriver"/> running the system should then be <see cref="Driver.FixedTimestepDriver.Reset"/>.
    /// </summary>
    /// <param name="system">A system with the same number of particles, and the same force generators for the same run.</param>
    /// <param name="integrator">
    /// The integrator to restore too, or null for the particles only. It must have the captured integrator's name;
    /// one that carries state (<see cref="IStatefulIntegrator"/>) needs a snapshot captured with it.
    /// </param>
    /// <exception cref="ArgumentException">The particle count, integrator name or integrator state does not match.</exception>
    public void RestoreTo(ParticleWorld system, IIntegrator? integrator = null)
    {
        Guard.NotNull(system, nameof(system));
        system.ThrowIfStepping();
        if (system.Count != ParticleCount)
        {
            throw new ArgumentException(
                $"The snapshot holds {ParticleCount} particles but the system has {system.Count}: "
                + "restore into a system built the same way.",
                nameof(system));
        }

        if (integrator is not null)
        {
            if (IntegratorName is not null && integrator.Name != IntegratorName)
            {
                throw new ArgumentException(
                    $"The snapshot was captured with the integrator '{IntegratorName}', not '{integrator.Name}'.",
                    nameof(integrator));
            }

            if (integrator is IStatefulIntegrator stateful)
            {
                if (IntegratorName is null)
                {
                    throw new ArgumentException(
                        $"The integrator '{integrator.Name}' carries state, but the snapshot was captured without an "
                        + "integrator: pass null to restore the particles only.",
                        nameof(integrator));
                }

                // Checks the length and the values before changing anything (the length may follow the system, as an
                // implicit integrator's warm start does); the particle data below was checked when captured or read.
                stateful.ReadState(_integratorState);
            }
            else if (_integratorState.Length != 0)
            {
                throw new ArgumentException(
                    $"The snapshot holds integrator state, but '{integrator.Name}' does not take any.", nameof(integrator));
            }
        }

        // Nothing below can fail: the masses and the state were checked when captured or read, and the world is not
        // in a step (checked above), so the integrator's state, read first, is never left restored alone.
        for (var i = 0; i < _masses.Length; i++)
        {
            system.SetMass(i, _masses[i]);
            system.SetRadius(i, _radii[i]);
            if (_pinned[i])
            {
                system.Pin(i);
            }
            else
            {
                system.Unpin(i);
            }
        }

        system.SetState(_state);
        system.Time = Time;
    }

    /// <summary>The number of bytes <see cref="WriteTo"/> writes.</summary>
    public int SerializedLength =>
        HeaderSize + Encoding.UTF8.GetByteCount(IntegratorName ?? string.Empty) + (BytesPerParticle(FormatVersion) * ParticleCount)
        + (8 * _integratorState.Length) + ChecksumSize;

    /// <summary>Writes the snapshot to <paramref name="stream"/> in the binary format described on the class.</summary>
    public void WriteTo(Stream stream)
    {
        Guard.NotNull(stream, nameof(stream));
        var bytes = new byte[SerializedLength];
        var span = bytes.AsSpan();
        var n = ParticleCount;
        var name = Encoding.UTF8.GetBytes(IntegratorName ?? string.Empty);
        _magic.CopyTo(span);
        BinaryPrimitives.WriteUInt16LittleEndian(span.Slice(4), FormatVersion);
        BinaryPrimitives.WriteUInt16LittleEndian(span.Slice(6), 0);
        BinaryPrimitives.WriteInt32LittleEndian(span.Slice(8), n);
        BinaryPrimitives.WriteInt32LittleEndian(span.Slice(12), name.Length);
        BinaryPrimitives.WriteInt32LittleEndian(span.Slice(16), _integratorState.Length);
        BinaryPrimitives.WriteInt64LittleEndian(span.Slice(20), BitConverter.DoubleToInt64Bits(Time));
        var o = HeaderSize;
        name.CopyTo(span.Slice(o));
        o += name.Length;
        o = WriteDoubles(span, o, _state);
        o = WriteDoubles(span, o, _masses);
        for (var i = 0; i < n; i++)
        {
            span[o++] = _pinned[i] ? (byte)1 : (byte)0;
        }

        o = WriteDoubles(span, o, _radii);
        o = WriteDoubles(span, o, _integratorState);
        BinaryPrimitives.WriteUInt32LittleEndian(span.Slice(o), Crc32.Compute(span.Slice(0, o)));
        stream.Write(bytes, 0, bytes.Length);
    }

    /// <summary>
    /// Reads a snapshot written by <see cref="WriteTo"/>, checking it completely: it reads exactly the snapshot's bytes
    /// and no further, so several snapshots can follow one another in a stream.
    /// </summary>
    /// <exception cref="InvalidDataException">
    /// The stream ends early, is not a snapshot (magic), has another format version, impossible counts, a checksum
    /// that does not match, or values no system can hold (non-finite, a mass that is not positive). A pinned particle
    /// may have a velocity (a kinematic anchor the host drives). The message says which.
    /// </exception>
    public static SimulationSnapshot ReadFrom(Stream stream)
    {
        Guard.NotNull(stream, nameof(stream));
        var header = new byte[HeaderSize];
        ReadExactly(stream, header, 0, HeaderSize, "the header");
        if (!header.AsSpan(0, 4).SequenceEqual(_magic))
        {
            throw new InvalidDataException(
                $"Not a ParticlePhysics snapshot: the stream starts with 0x{Hex(header.AsSpan(0, 4))}, not \"PPSN\".");
        }

        int version = BinaryPrimitives.ReadUInt16LittleEndian(header.AsSpan(4));
        if (version < OldestReadableVersion || version > FormatVersion)
        {
            throw new InvalidDataException(version > FormatVersion
                ? $"The snapshot has format version {version}, newer than this library reads ({OldestReadableVersion} to {FormatVersion}): update the library."
                : $"The snapshot has format version {version}, which does not exist (this library reads {OldestReadableVersion} to {FormatVersion}).");
        }

        int flags = BinaryPrimitives.ReadUInt16LittleEndian(header.AsSpan(6));
        var n = BinaryPrimitives.ReadInt32LittleEndian(header.AsSpan(8));
        var nameLength = BinaryPrimitives.ReadInt32LittleEndian(header.AsSpan(12));
        var m = BinaryPrimitives.ReadInt32LittleEndian(header.AsSpan(16));
        if (flags != 0)
        {
            throw new InvalidDataException($"The snapshot's flags are 0x{flags:X4}; version {version} defines none.");
        }

        if (n < 0 || n > ParticleWorld.MaxParticles)
        {
            throw new InvalidDataException(
                $"The snapshot's particle count {n} is impossible (0 to {ParticleWorld.MaxParticles} allowed).");
        }

        if (nameLength < 0 || nameLength > MaxIntegratorNameLength)
        {
            throw new InvalidDataException(
                $"The snapshot's integrator name length {nameLength} is impossible (0 to {MaxIntegratorNameLength} allowed).");
        }

        if (m < 0 || m > MaxIntegratorStateLength(n))
        {
            throw new InvalidDataException(
                $"The snapshot's integrator state length {m} is impossible (0 to {MaxIntegratorStateLength(n)} allowed).");
        }

        var total = HeaderSize + nameLength + (BytesPerParticle(version) * n) + (8 * m) + ChecksumSize;
        if (stream.CanSeek && stream.Length - stream.Position < total - HeaderSize)
        {
            // Say so before allocating room for a count that a damaged header may have inflated.
            throw new InvalidDataException(
                $"The snapshot is truncated: its header announces {total} bytes for {n} particles, but only "
                + $"{HeaderSize + stream.Length - stream.Position} remain in the stream.");
        }

        var bytes = ReadPayload(stream, header, total, $"the payload of {n} particles");
        var span = bytes.AsSpan();
        var stored = BinaryPrimitives.ReadUInt32LittleEndian(span.Slice(total - ChecksumSize));
        var computed = Crc32.Compute(span.Slice(0, total - ChecksumSize));
        if (stored != computed)
        {
            throw new InvalidDataException(
                $"The snapshot is corrupted: its CRC-32 is 0x{stored:X8} but its bytes give 0x{computed:X8}.");
        }

        return Decode(span, version, n, nameLength, m);
    }

    /// <summary>The bytes per particle of a format version: state 48, mass 8, pinned flag 1, and from version 2 a radius 8.</summary>
    private static int BytesPerParticle(int version) => version >= 2 ? 65 : 57;

    private static SimulationSnapshot Decode(ReadOnlySpan<byte> span, int version, int n, int nameLength, int m)
    {
        var snapshot = new SimulationSnapshot
        {
            Time = BitConverter.Int64BitsToDouble(BinaryPrimitives.ReadInt64LittleEndian(span.Slice(20))),
            _state = new double[6 * n],
            _masses = new double[n],
            _pinned = new bool[n],
            _radii = new double[n],
            _integratorState = new double[m],
        };
        if (!DoubleChecks.IsFinite(snapshot.Time))
        {
            throw new InvalidDataException($"The snapshot's time is {Guard.Format(snapshot.Time)}; it must be finite.");
        }

        var o = HeaderSize;
        if (nameLength > 0)
        {
            try
            {
                snapshot.IntegratorName = new UTF8Encoding(false, true).GetString(span.Slice(o, nameLength).ToArray());
            }
            catch (ArgumentException e)
            {
                throw new InvalidDataException("The snapshot's integrator name is not valid UTF-8.", e);
            }
        }

        o += nameLength;
        o = ReadDoubles(span, o, snapshot._state);
        o = ReadDoubles(span, o, snapshot._masses);
        for (var i = 0; i < n; i++)
        {
            var flag = span.ForReading()[o++];
            if (flag > 1)
            {
                throw new InvalidDataException($"Particle {i}'s pinned flag is {flag}; it must be 0 or 1.");
            }

            snapshot._pinned[i] = flag == 1;
        }

        if (version >= 2)
        {
            o = ReadDoubles(span, o, snapshot._radii);
        }

        ReadDoubles(span, o, snapshot._integratorState);
        var bad = DoubleChecks.FirstNonFinite(snapshot._state);
        if (bad >= 0)
        {
            throw new InvalidDataException(
                $"Particle {(bad % (3 * n)) / 3}'s {(bad < 3 * n ? "position" : "velocity")} is not finite "
                + $"({Guard.Format(snapshot._state[bad])}).");
        }

        for (var i = 0; i < n; i++)
        {
            var mass = snapshot._masses[i];
            if (!(mass > 0.0) || !DoubleChecks.IsFinite(mass) || !DoubleChecks.IsFinite(1.0 / mass))
            {
                throw new InvalidDataException(
                    $"Particle {i}'s mass is {Guard.Format(mass)}; it must be a positive finite number of at least "
                    + $"{Guard.Format(Guard.SmallestMass)} kg (so that its inverse is finite).");
            }

            var radius = snapshot._radii[i];
            if (!(radius >= 0.0) || !DoubleChecks.IsFinite(radius))
            {
                throw new InvalidDataException(
                    $"Particle {i}'s radius is {Guard.Format(radius)}; it must be a finite number >= 0.");
            }
        }

        return snapshot;
    }

    /// <summary>
    /// Reads the whole snapshot of <paramref name="total"/> bytes, its header already read, into a buffer that grows with
    /// what the stream delivers (64 KiB, then doubling): a damaged header that announces millions of particles on a
    /// stream that ends early costs a few kilobytes, not the hundreds of megabytes it announced.
    /// </summary>
    private static byte[] ReadPayload(Stream stream, byte[] header, int total, string what)
    {
        var buffer = new byte[Math.Min(total, HeaderSize + ReadChunk)];
        header.CopyTo(buffer, 0);
        var filled = HeaderSize;
        while (filled < total)
        {
            if (filled == buffer.Length)
            {
                var grown = new byte[(int)Math.Min(total, 2L * buffer.Length)];
                Buffer.BlockCopy(buffer, 0, grown, 0, filled);
                buffer = grown;
            }

            var got = stream.Read(buffer, filled, buffer.Length - filled);
            if (got <= 0)
            {
                throw new InvalidDataException(
                    $"The snapshot is truncated: the stream ended after {filled} bytes, {total - filled} bytes "
                    + $"short of the end of {what} ({total} bytes).");
            }

            filled += got;
        }

        return buffer;
    }

    private static void ReadExactly(Stream stream, byte[] buffer, int offset, int count, string what)
    {
        var read = 0;
        while (read < count)
        {
            var got = stream.Read(buffer, offset + read, count - read);
            if (got <= 0)
            {
                throw new InvalidDataException(
                    $"The snapshot is truncated: the stream ended after {offset + read} bytes, {count - read} bytes "
                    + $"short of the end of {what} ({offset + count} bytes).");
            }

            read += got;
        }
    }

    private static int WriteDoubles(Span<byte> span, int offset, double[] values)
    {
        foreach (var value in values)
        {
            BinaryPrimitives.WriteInt64LittleEndian(span.Slice(offset), BitConverter.DoubleToInt64Bits(value));
            offset += 8;
        }

        return offset;
    }

    private static int ReadDoubles(ReadOnlySpan<byte> span, int offset, double[] values)
    {
        for (var i = 0; i < values.Length; i++)
        {
            values[i] = BitConverter.Int64BitsToDouble(BinaryPrimitives.ReadInt64LittleEndian(span.Slice(offset)));
            offset += 8;
        }

        return offset;
    }

    private static double[] Resize(double[] buffer, int length) => buffer.Length == length ? buffer : new double[length];

    private static string Hex(ReadOnlySpan<byte> bytes)
    {
        var text = new StringBuilder(2 * bytes.Length);
        var readable = bytes.ForReading();
        for (var i = 0; i < readable.Length; i++)
        {
            text.Append(readable[i].ToString("X2", System.Globalization.CultureInfo.InvariantCulture));
        }

        return text.ToString();
    }
}
