using System;
using System.Numerics;
using ParticlePhysics.Cloth;

namespace ParticlePhysics.Tests.Cloth;

/// <summary>A render mesh welded into a cloth's particles: the maps, the normals across a seam, the masses, and the refusals.</summary>
public class WeldedMeshTests
{
    // Two unit squares side by side, each its own two triangles with its own four vertices: the shared edge (x = 1) is a
    // UV seam, vertices 1 and 4, 2 and 7 at one position.
    private static readonly double[] _seamVertices =
    {
        0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1, // square A: 0..3
        1, 0, 0, 2, 0, 0, 2, 0, 1, 1, 0, 1, // square B: 4..7
    };

    private static readonly int[] _seamTriangles = { 0, 3, 1, 1, 3, 2, 4, 7, 5, 5, 7, 6 };

    [Fact]
    public void A_seam_is_welded_into_one_particle_per_position_with_the_maps_both_ways()
    {
        var mesh = new WeldedMesh(_seamVertices, _seamTriangles);
        Assert.Equal(8, mesh.VertexCount);
        Assert.Equal(6, mesh.ParticleCount);
        Assert.Equal(4, mesh.TriangleCount);
        Assert.Equal(new[] { 0, 1, 2, 3, 1, 4, 5, 2 }, mesh.ParticleOfVertex.ToArray());
        Assert.Equal(new[] { 0, 1, 2, 3, 5, 6 }, mesh.FirstVertexOfParticle.ToArray());
        Assert.Equal(new[] { 1, 4 }, mesh.VerticesOf(1).ToArray());
        Assert.Equal(new[] { 2, 7 }, mesh.VerticesOf(2).ToArray());
        Assert.Equal(new[] { 0 }, mesh.VerticesOf(0).ToArray());
        Assert.Equal(_seamTriangles, mesh.Triangles.ToArray());
        Assert.Equal(new[] { 0, 3, 1, 1, 3, 2, 1, 2, 4, 4, 2, 5 }, mesh.ParticleTriangles.ToArray());
    }

    [Fact]
    public void Render_vertices_of_a_seam_get_the_welded_particles_position_and_normal()
    {
        var cloth = new MeshClothBuilder(new WeldedMesh(_seamVertices, _seamTriangles)) { Gravity = 0 }.Build();

        // Fold the sheet about the seam: square B turns up by 90 degrees, so the seam's normal is the mean of both.
        var world = cloth.System;
        world.SetPosition(cloth.ParticleIndex(5), new Vector3d(1, 1, 0));
        world.SetPosition(cloth.ParticleIndex(6), new Vector3d(1, 1, 1));
        var vertices = new Vector3[8];
        var normals = new Vector3[8];
        cloth.WriteVertices(vertices);
        cloth.WriteNormals(normals);
        Assert.Equal(vertices[1], vertices[4]);
        Assert.Equal(vertices[2], vertices[7]);
        Assert.Equal(new Vector3(1, 1, 0), vertices[5]);
        Assert.Equal(normals[1], normals[4]);
        Assert.Equal(normals[2], normals[7]);

        // Area-weighted: particle 1 (vertices 1 and 4) has two triangles of A and one of B, particle 2 one of A and two of B.
        var faceA = Vector3.Normalize(Vector3.Cross(vertices[3] - vertices[0], vertices[1] - vertices[0]));
        var faceB = Vector3.Normalize(Vector3.Cross(vertices[7] - vertices[4], vertices[5] - vertices[4]));
        Assert.Equal(faceA, normals[0]);
        Assert.Equal(faceB, normals[5]);
        Assert.Equal(Vector3.UnitY, faceA);
        Assert.Equal(-Vector3.UnitX, faceB);
        var one = Vector3.Normalize((2 * faceA) + faceB);
        var two = Vector3.Normalize(faceA + (2 * faceB));
        Assert.True((normals[1] - one).Length() < 1e-6, $"seam normal {normals[1]}, expected {one}");
        Assert.True((normals[2] - two).Length() < 1e-6, $"seam normal {normals[2]}, expected {two}");
    }

    [Fact]
    public void Masses_are_lumped_a_third_of_each_triangle_to_each_corner()
    {
        var builder = new MeshClothBuilder(new WeldedMesh(_seamVertices, _seamTriangles)) { AreaDensity = 3 };
        var masses = builder.ParticleMasses();

        // Area 2 m^2 at 3 kg/m^2: 6 kg; each triangle of 0.5 m^2 gives 0.5 kg to each corner.
        Assert.Equal(6.0, builder.TotalMass, 12);
        Assert.Equal(new[] { 0.5, 1.5, 1.5, 1.0, 1.0, 0.5 }, masses);
        builder.TotalMass = 12;
        Assert.Equal(new[] { 1.0, 3.0, 3.0, 2.0, 2.0, 1.0 }, builder.ParticleMasses());
        builder.MassDistribution = ClothMassDistribution.Uniform;
        Assert.All(builder.ParticleMasses(), m => Assert.Equal(2.0, m));
    }

    [Fact]
    public void Edges_of_three_triangles_are_allowed()
    {
        // A fin: three triangles on the edge 0-1.
        double[] vertices = { 0, 0, 0, 1, 0, 0, 0.5, 0, 1, 0.5, 1, 0, 0.5, 0, -1 };
        var mesh = new WeldedMesh(vertices, new[] { 0, 1, 2, 0, 1, 3, 0, 1, 4 });
        var cloth = new MeshClothBuilder(mesh) { BendingRigidity = 1e-3 }.Build();
        cloth.System.Step(new global::ParticlePhysics.Integrators.ImplicitEuler(), 0.01);
        Assert.True(cloth.System.GetPosition(4).IsFinite);
    }

    [Fact]
    public void Bad_meshes_are_refused_naming_the_vertex_or_triangle()
    {
        double[] square = { 0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1 };
        Check(ClothMeshProblem.MissingVertex, 1, 4, () => new WeldedMesh(square, new[] { 0, 1, 2, 0, 2, 4 }), "names vertex 4");
        Check(ClothMeshProblem.DegenerateTriangle, 0, -1, () => new WeldedMesh(square, new[] { 0, 1, 1, 0, 2, 3 }), "degenerate");
        double[] line = { 0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 0, 1 };
        Check(ClothMeshProblem.DegenerateTriangle, 0, -1, () => new WeldedMesh(line, new[] { 0, 1, 2, 0, 1, 3 }), "no area");
        Check(ClothMeshProblem.UnusedVertex, -1, 3, () => new WeldedMesh(square, new[] { 0, 1, 2 }), "used by no triangle");
        double[] nan = { 0, 0, 0, 1, 0, double.NaN, 1, 0, 1, 0, 0, 1 };
        Check(ClothMeshProblem.NonFiniteVertex, -1, 1, () => new WeldedMesh(nan, new[] { 0, 1, 2, 0, 2, 3 }), "finite");
        Check(ClothMeshProblem.DuplicateVertex, -1, 4, () => new WeldedMesh(_seamVertices, _seamTriangles, weld: false), "Vertices 1 and 4");
        Check(ClothMeshProblem.Shape, -1, -1, () => new WeldedMesh(square, Array.Empty<int>()), "no triangle");
        Check(ClothMeshProblem.Shape, -1, -1, () => new WeldedMesh(new double[] { 0, 0 }, new[] { 0, 0, 0 }), "3 coordinates");

        // Welding that folds a triangle onto itself is degenerate too.
        double[] folded = { 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 1 };
        Check(ClothMeshProblem.DegenerateTriangle, 0, -1, () => new WeldedMesh(folded, new[] { 0, 1, 2, 0, 1, 3 }), "welded");
    }

    private static void Check(ClothMeshProblem problem, int triangle, int vertex, Func<WeldedMesh> make, string message)
    {
        var e = Assert.Throws<ClothMeshException>(() => make());
        Assert.Equal(problem, e.Problem);
        Assert.Equal(triangle, e.Triangle);
        Assert.Equal(vertex, e.Vertex);
        Assert.Contains(message, e.Message, StringComparison.Ordinal);
    }
}
