using System;
using ParticlePhysics.Constraints;

namespace ParticlePhysics.Bodies;

/// <summary>
/// The particles that fill a solid: a box of size s at spacing h holds round(s_a / h) particles along each of its axes
/// a (at least 1), at the cell centres -s / 2 + (i + 1/2) h of the box's own frame, x fastest, then y, then z (the
/// scene format's rule), each of radius h / 2.
/// </summary>
public static class BodyLattice
{
    /// <summary>The most particles one lattice makes.</summary>
    public const int MaxParticles = 16 * 1024 * 1024;

    /// <summary>The number of particles along each axis of a box of <paramref name="size"/> at <paramref name="spacing"/>.</summary>
    /// <exception cref="ArgumentException">A size or the spacing is not positive and finite, or the box would hold more than <see cref="MaxParticles"/>.</exception>
    public static (int X, int Y, int Z) BoxCounts(Vector3d size, double spacing)
    {
        Guard.PositiveFinite(spacing, nameof(spacing));
        if (!(size.X > 0.0 && size.Y > 0.0 && size.Z > 0.0) || !size.IsFinite)
        {
            throw new ArgumentException($"size must have three positive finite sides, in m; got {size}.", nameof(size));
        }

        var nx = Count(size.X, spacing);
        var ny = Count(size.Y, spacing);
        var nz = Count(size.Z, spacing);
        if ((double)nx * ny * nz > MaxParticles)
        {
            throw new ArgumentException(
                $"A box of {size} at spacing {Guard.Format(spacing)} m would hold {(double)nx * ny * nz} particles; at most {MaxParticles}: give a larger spacing.", nameof(spacing));
        }

        return (nx, ny, nz);
    }

    /// <summary>
    /// The particles' offsets in the box's own frame (from its centre), in lattice order: what
    /// <see cref="ShapeMatching.AddRigid"/> keeps as the body's rest shape.
    /// </summary>
    public static Vector3d[] BoxOffsets(Vector3d size, double spacing)
    {
        var (nx, ny, nz) = BoxCounts(size, spacing);
        var offsets = new Vector3d[nx * ny * nz];
        var k = 0;
        for (var z = 0; z < nz; z++)
        {
            for (var y = 0; y < ny; y++)
            {
                for (var x = 0; x < nx; x++)
                {
                    offsets[k++] = new Vector3d(
                        (-0.5 * size.X) + ((x + 0.5) * spacing), (-0.5 * size.Y) + ((y + 0.5) * spacing), (-0.5 * size.Z) + ((z + 0.5) * spacing));
                }
            }
        }

        return offsets;
    }

    /// <summary>The particles' world positions for a box at <paramref name="center"/> turned by <paramref name="rotation"/>.</summary>
    public static Vector3d[] Box(Vector3d center, Vector3d size, Rotation3d rotation, double spacing)
    {
        Guard.Finite(center, nameof(center));
        var offsets = BoxOffsets(size, spacing);
        for (var k = 0; k < offsets.Length; k++)
        {
            offsets[k] = center + rotation.Rotate(offsets[k]);
        }

        return offsets;
    }

    private static int Count(double side, double spacing)
    {
        var n = Math.Round(side / spacing, MidpointRounding.AwayFromZero);
        return n < 1.0 ? 1 : n > MaxParticles ? MaxParticles + 1 : (int)n;
    }
}
