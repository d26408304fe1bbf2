using System.Runtime.CompilerServices;

namespace ParticlePhysics.Contacts;

/// <summary>
/// The normal of a particle pair, from b to a: the line of centres, d / |d| with d = x_a - x_b, and for two particles
/// at exactly the same point (spawned there) a direction from their indices, so that they separate.
/// </summary>
/// <remarks>
/// Coincident particles have no line of centres. A fixed direction (+y, as for a sphere's centre) sends every such
/// pair the same way: a hundred particles spawned at one point could only spread into a column, and with the ground
/// under them, pushes up and down cancelled and pairs stayed exactly coincident. Here each particle i has a point
/// h(i) in [-1, 1)^3, three 21-bit fields of a SplitMix64 hash of i, and the pair's normal is (h(a) - h(b)) / |h(a) - h(b)|:
/// antisymmetric (the pair seen from b is the opposite normal), the same on every run and machine (integer hashing,
/// one square root), and every partner pushes a particle the same way, towards its own h, so that a heap spawned at
/// one point opens in all directions at once.
/// </remarks>
internal static class PairNormal
{
    /// <summary>|d| and the unit normal from b to a: d / |d|, or the indices' direction when d = 0.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static double Of(double dx, double dy, double dz, int a, int b, out double nx, out double ny, out double nz)
    {
        var length = System.Math.Sqrt((dx * dx) + (dy * dy) + (dz * dz));
        if (length > 0.0)
        {
            nx = dx / length;
            ny = dy / length;
            nz = dz / length;
            return length;
        }

        Coincident(a, b, out nx, out ny, out nz);
        return 0.0;
    }

    /// <summary>The direction of two coincident particles: (h(a) - h(b)) / |h(a) - h(b)|, or +-y should the two hash alike.</summary>
    public static void Coincident(int a, int b, out double nx, out double ny, out double nz)
    {
        Point(a, out var ax, out var ay, out var az);
        Point(b, out var bx, out var by, out var bz);
        double dx = ax - bx, dy = ay - by, dz = az - bz;
        var length = System.Math.Sqrt((dx * dx) + (dy * dy) + (dz * dz));
        if (length > 0.0)
        {
            nx = dx / length;
            ny = dy / length;
            nz = dz / length;
        }
        else
        {
            nx = 0.0;
            ny = a < b ? 1.0 : -1.0;
            nz = 0.0;
        }
    }

    /// <summary>h(i): three 21-bit fields of SplitMix64(i), each k / 2^20 - 1 (exact in a double).</summary>
    private static void Point(int i, out double x, out double y, out double z)
    {
        var h = (ulong)(uint)i + 0x9E3779B97F4A7C15UL;
        h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9UL;
        h = (h ^ (h >> 27)) * 0x94D049BB133111EBUL;
        h ^= h >> 31;
        const double scale = 1.0 / (1 << 20);
        x = ((h >> 43) * scale) - 1.0;
        y = (((h >> 22) & 0x1FFFFF) * scale) - 1.0;
        z = (((h >> 1) & 0x1FFFFF) * scale) - 1.0;
    }
}
