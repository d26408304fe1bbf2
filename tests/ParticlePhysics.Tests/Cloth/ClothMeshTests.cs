using System;
using System.Collections.Generic;
using System.Numerics;
using ParticlePhysics.Cloth;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Tests.Cloth;

/// <summary>The cloth's render data: index buffer and area-weighted vertex normals.</summary>
public class ClothMeshTests
{
    [Theory]
    [InlineData(2, 2)]
    [InlineData(3, 5)]
    [InlineData(11, 11)]
    public void The_index_buffer_has_two_valid_consistently_wound_triangles_per_cell(int rows, int columns)
    {
        var mesh = new ClothMesh(rows, columns);
        var indices = mesh.CreateTriangles();
        Assert.Equal(6 * (rows - 1) * (columns - 1), indices.Length);
        Assert.Equal(indices.Length, mesh.IndexCount);

        // Consistent winding: every directed edge is used once; an inner edge's reverse is used by its neighbour.
        var directed = new HashSet<(int, int)>();
        for (var t = 0; t < indices.Length; t += 3)
        {
            int a = indices[t], b = indices[t + 1], c = indices[t + 2];
            Assert.All(new[] { a, b, c }, i => Assert.InRange(i, 0, (rows * columns) - 1));
            Assert.True(a != b && b != c && a != c, $"triangle {t / 3} is degenerate");
            Assert.True(directed.Add((a, b)) && directed.Add((b, c)) && directed.Add((c, a)), "a directed edge is used twice");
        }

        var shared = 0;
        foreach (var (a, b) in directed)
        {
            shared += directed.Contains((b, a)) ? 1 : 0;
        }

        // Inner edges: (r-1)(c-2) + (r-2)(c-1) grid edges and one diagonal per cell, each counted in both directions.
        var inner = ((rows - 1) * (columns - 2)) + ((rows - 2) * (columns - 1)) + ((rows - 1) * (columns - 1));
        Assert.Equal(2 * inner, shared);

        // On the flat cloth as built, every triangle faces +y.
        var cloth = new ClothBuilder { Rows = rows, Columns = columns }.Build();
        var vertices = new Vector3[cloth.ParticleCount];
        cloth.WriteVertices(vertices);
        for (var t = 0; t < indices.Length; t += 3)
        {
            var p0 = vertices[indices[t]];
            var face = Vector3.Cross(vertices[indices[t + 1]] - p0, vertices[indices[t + 2]] - p0);
            Assert.True(face.Y > 0 && face.X == 0 && face.Z == 0, $"triangle {t / 3}: {face}");
        }
    }

    [Fact]
    public void A_flat_cloth_has_normals_straight_up_and_its_mirror_image_straight_down()
    {
        var cloth = new ClothBuilder { Rows = 4, Columns = 6, Spacing = 0.3 }.Build();
        var vertices = new Vector3[cloth.ParticleCount];
        var normals = new Vector3[cloth.ParticleCount];
        cloth.WriteVertices(vertices);
        cloth.Mesh.ComputeNormals(vertices, normals);
        Assert.All(normals, n => Assert.Equal(Vector3.UnitY, n));

        for (var i = 0; i < vertices.Length; i++)
        {
            vertices[i].Z = -vertices[i].Z; // a mirror image reverses the winding
        }

        cloth.Mesh.ComputeNormals(vertices, normals);
        Assert.All(normals, n => Assert.Equal(-Vector3.UnitY, n));
    }

    [Fact]
    public void A_folded_cloth_has_area_weighted_normals()
    {
        // Two rows (z = 0, 1) of three columns: x = 0, 1, 3 at heights y = 0, 1, 0, a tent with a narrow left panel
        // (face cross product (-1, 1, 0), length sqrt 2 = twice each triangle's area) and a wide right one ((1, 2, 0)).
        var mesh = new ClothMesh(2, 3);
        var vertices = new[]
        {
            new Vector3(0, 0, 0), new Vector3(1, 1, 0), new Vector3(3, 0, 0),
            new Vector3(0, 0, 1), new Vector3(1, 1, 1), new Vector3(3, 0, 1),
        };
        var normals = new Vector3[6];
        mesh.ComputeNormals(vertices, normals);
        var left = new Vector3(-1, 1, 0);
        var right = new Vector3(1, 2, 0);

        // Vertex 1 is in two left triangles and one right one, vertex 4 in one left and two right.
        AssertClose(Vector3.Normalize(left), normals[0]);
        AssertClose(Vector3.Normalize(left), normals[3]);
        AssertClose(Vector3.Normalize((2 * left) + right), normals[1]);
        AssertClose(Vector3.Normalize(left + (2 * right)), normals[4]);
        AssertClose(Vector3.Normalize(right), normals[2]);
        AssertClose(Vector3.Normalize(right), normals[5]);
    }

    [Fact]
    public void A_hanging_cloth_has_unit_normals()
    {
        var cloth = new ClothBuilder { Rows = 6, Columns = 6 }.Build();
        var rk4 = new RungeKutta4();
        for (var s = 0; s < 300; s++)
        {
            cloth.System.Step(rk4, 0.002);
        }

        var vertices = new Vector3[cloth.ParticleCount];
        var normals = new Vector3[cloth.ParticleCount];
        cloth.WriteVertices(vertices);
        cloth.Mesh.ComputeNormals(vertices, normals);
        Assert.All(normals, n => Assert.Equal(1f, n.Length(), 5));
    }

    [Fact]
    public void Degenerate_triangles_give_a_default_normal_and_bad_buffers_are_refused()
    {
        var mesh = new ClothMesh(2, 2);
        var normals = new Vector3[4];
        mesh.ComputeNormals(new Vector3[4], normals);
        Assert.All(normals, n => Assert.Equal(Vector3.UnitY, n));
        Assert.Equal("vertices", Assert.Throws<ArgumentException>(() => mesh.ComputeNormals(new Vector3[3], normals)).ParamName);
        Assert.Equal("normals", Assert.Throws<ArgumentException>(() => mesh.ComputeNormals(new Vector3[4], new Vector3[3])).ParamName);
        Assert.Equal("indices", Assert.Throws<ArgumentException>(() => mesh.WriteTriangles(new int[5])).ParamName);
        Assert.Equal("rows", Assert.Throws<ArgumentOutOfRangeException>(() => new ClothMesh(1, 5)).ParamName);
    }

    private static void AssertClose(Vector3 expected, Vector3 actual)
    {
        Assert.True(Vector3.Distance(expected, actual) < 1e-6f, $"expected {expected}, got {actual}");
    }
}
