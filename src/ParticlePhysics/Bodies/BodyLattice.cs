using System;
using System.Collections.Generic;
using ParticlePhysics.Constraints;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Bodies;

/// <summary>
/// The particles that fill a solid: a box of size s at spacing h holds round(s_a / h) particles along each of its axes
/// a (at least 1), at the cell centres -s / 2 + (i + 1/2) h of the box's own frame, x fastest, then y, then z (the
/// scene format's rule), each of radius h / 2. A closed mesh holds the cells of that rule over its bounding box
/// whose centres lie inside it, in the same order.
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

    /// <summary>
    /// The particles that fill a closed triangle mesh at <paramref name="spacing"/>: the cells of the box rule over the
    /// mesh's bounding box whose centres lie inside it (the mesh's winding number there is above one half, so a mesh
    /// facing inwards fills as well), in lattice order.
    /// </summary>
    /// <param name="vertices">The mesh's vertices, m.</param>
    /// <param name="triangles">Three vertex indices per triangle.</param>
    /// <param name="spacing">The lattice's spacing h, m.</param>
    /// <exception cref="ArgumentException">
    /// A vertex is not finite, a triangle names a missing vertex, the mesh is not closed (an edge borders more
    /// triangles on one side than on the other), or no cell centre lies inside it (the spacing is too coarse).
    /// </exception>
    /// <remarks>Each cell looks at every triangle: a mesh of T triangles filled with N cells costs N T solid angles, once.</remarks>
    public static Vector3d[] Mesh(ReadOnlySpan<Vector3d> vertices, ReadOnlySpan<int> triangles, double spacing)
    {
        var x = vertices.ForReading();
        var corners = triangles.ForReading();
        CheckClosed(x, corners);
        var low = x[0];
        var high = x[0];
        foreach (var v in x)
        {
            low = new Vector3d(Math.Min(low.X, v.X), Math.Min(low.Y, v.Y), Math.Min(low.Z, v.Z));
            high = new Vector3d(Math.Max(high.X, v.X), Math.Max(high.Y, v.Y), Math.Max(high.Z, v.Z));
        }

        var size = high - low;
        var offsets = BoxOffsets(new Vector3d(Math.Max(size.X, spacing), Math.Max(size.Y, spacing), Math.Max(size.Z, spacing)), spacing);
        var centre = 0.5 * (low + high);
        var inside = new List<Vector3d>();
        foreach (var offset in offsets)
        {
            var p = centre + offset;
            if (Math.Abs(WindingNumber.At(p, x, corners)) > 0.5)
            {
                inside.Add(p);
            }
        }

        if (inside.Count == 0)
        {
            throw new ArgumentException($"No lattice cell centre at spacing {Guard.Format(spacing)} m lies inside the mesh (its bounding box is {size} m): give a smaller spacing.", nameof(spacing));
        }

        return inside.ToArray();
    }

    /// <summary>The volume a closed mesh encloses, m^3 (by the divergence theorem; positive whichever way its triangles face).</summary>
    /// <exception cref="ArgumentException">As for <see cref="Mesh"/>: a vertex not finite, a missing vertex, a mesh not closed.</exception>
    public static double MeshVolume(ReadOnlySpan<Vector3d> vertices, ReadOnlySpan<int> triangles)
    {
        var x = vertices.ForReading();
        var corners = triangles.ForReading();
        CheckClosed(x, corners);

        // Each triangle with a fixed point o spans a tetrahedron of signed volume a . (b x c) / 6 (corners from o); a
        // closed surface sums them to its volume. o is the first vertex, so that a mesh far from the origin keeps its digits.
        var o = x[0];
        var sum = 0.0;
        for (var t = 0; t < corners.Length; t += 3)
        {
            sum += Vector3d.Dot(x[corners[t]] - o, Vector3d.Cross(x[corners[t + 1]] - o, x[corners[t + 2]] - o));
        }

        return Math.Abs(sum) / 6.0;
    }

    // Closed: every edge borders as many triangles in one direction as in the other, so the surface has no boundary.
    private static void CheckClosed(Span<Vector3d> vertices, Span<int> triangles)
    {
        if (vertices.Length == 0 || triangles.Length == 0 || triangles.Length % 3 != 0)
        {
            throw new ArgumentException($"A mesh needs vertices and triangles of three vertex indices each; got {vertices.Length} vertices and {triangles.Length} indices.", nameof(triangles));
        }

        for (var i = 0; i < vertices.Length; i++)
        {
            if (!vertices[i].IsFinite)
            {
                throw new ArgumentException($"Vertex {i} is {vertices[i]}; vertices must be finite.", nameof(vertices));
            }
        }

        var balance = new Dictionary<(int, int), int>();
        for (var t = 0; t < triangles.Length; t++)
        {
            var a = triangles[t];
            var b = triangles[t % 3 == 2 ? t - 2 : t + 1];
            if ((uint)a >= (uint)vertices.Length)
            {
                throw new ArgumentException($"Triangle {t / 3} names vertex {a}; the mesh has vertices 0 to {vertices.Length - 1}.", nameof(triangles));
            }

            var key = a < b ? (a, b) : (b, a);
            balance[key] = (balance.TryGetValue(key, out var n) ? n : 0) + (a < b ? 1 : -1);
        }

        foreach (var edge in balance)
        {
            if (edge.Value != 0)
            {
                throw new ArgumentException(
                    $"The mesh is not closed: its edge from vertex {edge.Key.Item1} to vertex {edge.Key.Item2} borders {Math.Abs(edge.Value)} more triangle(s) on one side than on the other; a solid needs a closed mesh.",
                    nameof(triangles));
            }
        }
    }

    private static int Count(double side, double spacing)
    {
        var n = Math.Round(side / spacing, MidpointRounding.AwayFromZero);
        return n < 1.0 ? 1 : n > MaxParticles ? MaxParticles + 1 : (int)n;
    }
}
