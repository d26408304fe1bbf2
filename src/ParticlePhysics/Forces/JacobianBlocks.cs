using System;

namespace ParticlePhysics.Forces;

/// <summary>
/// Adds 3 x 3 blocks of the form s I + t u u^T to the per-particle diagonal blocks (9 values per particle,
/// row-major) that the implicit integrator's block-Jacobi preconditioner inverts.
/// </summary>
internal static class JacobianBlocks
{
    public static void AddIsotropic(Span<double> blocks, int particle, double s)
    {
        var o = 9 * particle;
        blocks[o] += s;
        blocks[o + 4] += s;
        blocks[o + 8] += s;
    }

    public static void Add(Span<double> blocks, int particle, double s, double t, double ux, double uy, double uz)
    {
        var o = 9 * particle;
        double xy = t * ux * uy, xz = t * ux * uz, yz = t * uy * uz;
        blocks[o] += s + (t * ux * ux);
        blocks[o + 1] += xy;
        blocks[o + 2] += xz;
        blocks[o + 3] += xy;
        blocks[o + 4] += s + (t * uy * uy);
        blocks[o + 5] += yz;
        blocks[o + 6] += xz;
        blocks[o + 7] += yz;
        blocks[o + 8] += s + (t * uz * uz);
    }
}
