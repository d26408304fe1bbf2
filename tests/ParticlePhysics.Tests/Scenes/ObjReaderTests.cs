using System;
using System.IO;
using System.Text;
using ParticlePhysics.Scenes;
using ParticlePhysics.Scenes.Meshes;

namespace ParticlePhysics.Tests.Scenes;

/// <summary>The OBJ reader: the forms it reads, what it ignores, and errors that name the file and the line.</summary>
public class ObjReaderTests
{
    private static TriangleMesh Read(string text) => ObjReader.Read(new MemoryStream(Encoding.UTF8.GetBytes(text)), "mesh.obj");

    [Fact]
    public void Reads_vertices_and_triangles_in_every_corner_form()
    {
        var mesh = Read(
            "# a comment\nmtllib a.mtl\no square\ng side\nv 0 0 0\nv 1 0 0\r\nv 1 1 0 1.0\nv 0 1 0 0.5 0.5 0.5\n"
            + "vt 0 0\nvn 0 0 1\nusemtl red\ns 1\nf 1 2/1 3//1\nf 1/1/1 3/1/1 4/1/1\n");
        Assert.Equal(new double[] { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0 }, mesh.Vertices);
        Assert.Equal(new[] { 0, 1, 2, 0, 2, 3 }, mesh.Triangles);
    }

    [Fact]
    public void Fans_a_polygon_and_counts_negative_indices_back_from_the_last_vertex()
    {
        var mesh = Read("v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\nf -5 -4 -3 -2 -1\n");
        Assert.Equal(new[] { 0, 1, 2, 0, 2, 3, 0, 3, 4 }, mesh.Triangles);
        Assert.Equal(new Vector3d(2, 1, 0), mesh.Vertex(2));
    }

    [Fact]
    public void Reads_numbers_as_the_invariant_culture_writes_them_to_the_last_bit()
    {
        var mesh = Read("v 0.1 -2.5e-3 1E10\nv 6.123233995736766E-17 -0 3\nv 1 1 1\nf 1 2 3\n");
        Assert.Equal(new[] { 0.1, -2.5e-3, 1e10, 6.123233995736766E-17, -0.0, 3, 1, 1, 1 }, mesh.Vertices);
    }

    [Theory]
    [InlineData("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", 4, "a face names vertex 4, and the file defines 3")]
    [InlineData("v 0 0 0\nv 1 0 0\nf 1 2\n", 3, "a face has 2 vertices; it needs at least 3")]
    [InlineData("v 0 0\n", 1, "a vertex has 2 numbers")]
    [InlineData("v 0 0 zero\n", 1, "'zero' is not a finite number")]
    [InlineData("v 0 0 1e999\n", 1, "'1e999' is not a finite number")]
    [InlineData("v 0 0 0\nf 0 1 1\n", 2, "'0' is not a vertex reference")]
    [InlineData("v 0 0 0\nf 1 -3 1\n", 2, "vertex -3 counts back past the first vertex")]
    [InlineData("v 0 0 0\nf 1 a/1 1\n", 2, "'a/1' is not a vertex reference")]
    [InlineData("v 0 0 0\nl 1 2\n", 2, "'l' is not a statement this reader takes")]
    public void A_malformed_file_is_refused_naming_the_line(string text, int line, string problem)
    {
        var error = Assert.Throws<SceneException>(() => Read(text));
        Assert.Equal("mesh.obj", error.File);
        Assert.Equal(line, error.Line);
        Assert.Contains(problem, error.Message, StringComparison.Ordinal);
        Assert.StartsWith($"mesh.obj:{line}", error.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void A_missing_file_is_refused_with_its_name()
    {
        var error = Assert.Throws<SceneException>(() => ObjReader.Read("no-such-mesh.obj"));
        Assert.StartsWith("no-such-mesh.obj: cannot read this OBJ file: ", error.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void A_line_across_two_blocks_is_read_whole_and_one_over_the_limit_is_refused()
    {
        // 600 kB of vertices, then a face of 700 kB: it starts in the reader's first 1 MB block and ends in the next.
        var text = new StringBuilder();
        while (text.Length < 600_000)
        {
            text.Append("v 0.125 0.25 0.5\n");
        }

        text.Append('f');
        for (var k = 0; k < 40_000; k++)
        {
            text.Append(" 1/1/1 2/2/2 3/3/3");
        }

        var mesh = Read(text.Append('\n').ToString());
        Assert.Equal(120_000 - 2, mesh.TriangleCount);

        var error = Assert.Throws<SceneException>(() => Read("v 0 0 0\nf" + string.Concat(System.Linq.Enumerable.Repeat(" 1 1 1", 200_000)) + "\n"));
        Assert.Equal("mesh.obj:2: a line longer than 1,048,576 bytes", error.Message);
    }

    [Fact]
    public void Bytes_that_are_not_text_are_refused_not_crashed_on()
    {
        var random = new Random(5);
        for (var k = 0; k < 200; k++)
        {
            var bytes = new byte[random.Next(1, 400)];
            random.NextBytes(bytes);
            try
            {
                ObjReader.Read(new MemoryStream(bytes), "noise.obj");
            }
            catch (SceneException e)
            {
                Assert.StartsWith("noise.obj", e.Message, StringComparison.Ordinal);
            }
        }
    }
}
