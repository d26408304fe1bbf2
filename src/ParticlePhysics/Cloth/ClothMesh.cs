using System;
using System.Numerics;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Cloth;

/// <summary>
/// The render topology of a rows x columns grid of vertices (vertex (row, col) = row * columns + col): two triangles
/// per cell, and area-weighted vertex normals. The index buffer is made once; vertices and normals are written each
/// frame into the caller's <see cref="Vector3"/> spans, the layout Unity's Mesh.SetVertices and SetNormals take.
/// </summary>
/// <remarks>
/// Cell (row, col) with corners a = (row, col), b = (row + 1, col), c = (row, col + 1), d = (row + 1, col + 1) gives
/// the triangles (a, b, c) and (c, b, d). Each is wound so that cross(p1 - p0, p2 - p0) points to the cloth's front:
/// +y for the flat cloth as built (x along columns, z along rows). Unity draws front faces clockwise as seen
/// by the viewer, which is this winding seen from +y, so the side the normals point to is the side Unity draws.
/// Normal of a vertex: the sum, over the triangles that use it, of cross(p1 - p0, p2 - p0) (twice the triangle's area
/// times its unit normal, so larger triangles weigh more), normalised.
/// </remarks>
public sealed class ClothMesh
{
    /// <summary>The mesh of a rows x columns grid.</summary>
    /// <param name="rows">At least 2.</param>
    /// <param name="columns">At least 2.</param>
    public ClothMesh(int rows, int columns)
    {
        if (rows < 2)
        {
            throw new ArgumentOutOfRangeException(nameof(rows), rows, $"rows must be at least 2; got {rows}.");
        }

        if (columns < 2)
        {
            throw new ArgumentOutOfRangeException(nameof(columns), columns, $"columns must be at least 2; got {columns}.");
        }

        if ((long)rows * columns > ClothBuilder.MaxParticles)
        {
            throw new ArgumentOutOfRangeException(
                nameof(rows), $"rows x columns must be at most {ClothBuilder.MaxParticles}; got {rows} x {columns}.");
        }

        Rows = rows;
        Columns = columns;
    }

    /// <summary>The number of rows of vertices.</summary>
    public int Rows { get; }

    /// <summary>The number of columns of vertices.</summary>
    public int Columns { get; }

    /// <summary>The number of vertices: rows x columns.</summary>
    public int VertexCount => Rows * Columns;

    /// <summary>The number of triangles: 2 (rows - 1) (columns - 1).</summary>
    public int TriangleCount => 2 * (Rows - 1) * (Columns - 1);

    /// <summary>The length of the index buffer: 3 per triangle, 6 (rows - 1) (columns - 1).</summary>
    public int IndexCount => 3 * TriangleCount;

    /// <summary>A new index buffer (Unity's Mesh.SetTriangles takes it); make it once and keep it.</summary>
    public int[] CreateTriangles()
    {
        var indices = new int[IndexCount];
        WriteTriangles(indices);
        return indices;
    }

    /// <summary>Writes the index buffer into <paramref name="indices"/> (at least <see cref="IndexCount"/> values).</summary>
    public void WriteTriangles(Span<int> indices)
    {
        if (indices.Length < IndexCount)
        {
            throw new ArgumentException(
                $"indices must hold at least {IndexCount} values; it holds {indices.Length}.", nameof(indices));
        }

        var k = 0;
        for (var row = 0; row + 1 < Rows; row++)
        {
            for (var col = 0; col + 1 < Columns; col++)
            {
                var a = (row * Columns) + col;
                int b = a + Columns, c = a + 1, d = a + Columns + 1;
                indices[k++] = a;
                indices[k++] = b;
                indices[k++] = c;
                indices[k++] = c;
                indices[k++] = b;
                indices[k++] = d;
            }
        }
    }

    /// <summary>
    /// Writes the area-weighted, normalised vertex normals of the mesh whose vertex positions are
    /// <paramref name="vertices"/> into <paramref name="normals"/>. A vertex whose triangles all have zero area gets
    /// (0, 1, 0). Allocates nothing.
    /// </summary>
    /// <param name="vertices">At least <see cref="VertexCount"/> positions.</param>
    /// <param name="normals">At least <see cref="VertexCount"/> vectors; must not overlap <paramref name="vertices"/>.</param>
    public void ComputeNormals(ReadOnlySpan<Vector3> vertices, Span<Vector3> normals)
    {
        var n = VertexCount;
        if (vertices.Length < n)
        {
            throw new ArgumentException(
                $"vertices must hold at least {n} positions; it holds {vertices.Length}.", nameof(vertices));
        }

        if (normals.Length < n)
        {
            throw new ArgumentException(
                $"normals must hold at least {n} vectors; it holds {normals.Length}.", nameof(normals));
        }

        if (vertices.Overlaps(normals))
        {
            throw new ArgumentException("vertices and normals must be distinct buffers.", nameof(normals));
        }

        normals.Slice(0, n).Clear();
        for (var row = 0; row + 1 < Rows; row++)
        {
            for (var col = 0; col + 1 < Columns; col++)
            {
                var a = (row * Columns) + col;
                int b = a + Columns, c = a + 1, d = a + Columns + 1;
                AddFaceNormal(vertices, normals, a, b, c);
                AddFaceNormal(vertices, normals, c, b, d);
            }
        }

        for (var i = 0; i < n; i++)
        {
            var length = normals[i].Length();
            normals[i] = length > 0f && !float.IsInfinity(length) ? normals[i] / length : Vector3.UnitY;
        }
    }

    private static void AddFaceNormal(ReadOnlySpan<Vector3> vertices, Span<Vector3> normals, int i0, int i1, int i2)
    {
        var v = vertices.ForReading();
        var p0 = v[i0];
        var face = Vector3.Cross(v[i1] - p0, v[i2] - p0);
        normals[i0] += face;
        normals[i1] += face;
        normals[i2] += face;
    }
}
