using System;

namespace ParticlePhysics.Scenes.Meshes;

/// <summary>A triangle mesh as read from a file: vertex positions and triangles by vertex index (0-based).</summary>
public sealed class TriangleMesh
{
    /// <summary>Wraps the arrays (not copied).</summary>
    /// <param name="vertices">x, y, z of each vertex, in m.</param>
    /// <param name="triangles">Three vertex indices per triangle.</param>
    public TriangleMesh(double[] vertices, int[] triangles)
    {
        Vertices = vertices ?? throw new ArgumentNullException(nameof(vertices));
        Triangles = triangles ?? throw new ArgumentNullException(nameof(triangles));
    }

    /// <summary>x, y, z of each vertex, in m.</summary>
    public double[] Vertices { get; }

    /// <summary>Three vertex indices per triangle, in file order (a face of n vertices gives n - 2 triangles, fanned from its first).</summary>
    public int[] Triangles { get; }

    /// <summary>The number of vertices.</summary>
    public int VertexCount => Vertices.Length / 3;

    /// <summary>The number of triangles.</summary>
    public int TriangleCount => Triangles.Length / 3;

    /// <summary>The position of vertex <paramref name="index"/>.</summary>
    public Vector3d Vertex(int index) => new(Vertices[3 * index], Vertices[(3 * index) + 1], Vertices[(3 * index) + 2]);
}
