using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Snapshots;

/// <summary>
/// CRC-32 (IEEE 802.3, the zip and PNG checksum: reflected polynomial 0xEDB88320, initial value and final xor
/// 0xFFFFFFFF; "123456789" gives 0xCBF43926). Written here because netstandard2.1 has no CRC and the core takes no
/// package dependencies (System.IO.Hashing would be one).
/// </summary>
internal static class Crc32
{
    private static readonly uint[] _table = CreateTable();

    /// <summary>The CRC-32 of <paramref name="data"/>.</summary>
    public static uint Compute(ReadOnlySpan<byte> data)
    {
        var crc = 0xFFFFFFFFu;
        var bytes = data.ForReading();
        for (var i = 0; i < bytes.Length; i++)
        {
            crc = _table[(crc ^ bytes[i]) & 0xFF] ^ (crc >> 8);
        }

        return crc ^ 0xFFFFFFFFu;
    }

    private static uint[] CreateTable()
    {
        var table = new uint[256];
        for (var n = 0u; n < 256; n++)
        {
            var c = n;
            for (var k = 0; k < 8; k++)
            {
                c = (c & 1) != 0 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            }

            table[n] = c;
        }

        return table;
    }
}
