using System;
using System.Buffers.Binary;
using System.IO;
using System.Text;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Snapshots;

// The binary format of the class remarks: writing, and reading that checks everything before it returns.
public sealed partial class SimulationSnapshot
{
    private const int HeaderSize = 28;
    private const int ReadChunk = 64 * 1024;
    private const int ChecksumSize = 4;
    private static readonly byte[] _magic = { (byte)'P', (byte)'P', (byte)'S', (byte)'N' };

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
