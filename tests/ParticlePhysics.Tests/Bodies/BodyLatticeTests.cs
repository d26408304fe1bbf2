using System;
using System.Linq;
using ParticlePhysics.Bodies;
using ParticlePhysics.Constraints;

namespace ParticlePhysics.Tests.Bodies;

/// <summary>Filling solids with particles: a box by the scene format's rule, a closed mesh by its winding number.</summary>
public class BodyLatticeTests
{
    // A cube of side 2 about (0.3, -0.2, 0.1), its twelve triangles facing outwards.
    private static readonly Vector3d[] _cube = Enumerable.Range(0, 8)
        .Select(k => new Vector3d(0.3 + ((k & 1) == 0 ? -1 : 1), -0.2 + ((k & 2) == 0 ? -1 : 1), 0.1 + ((k & 4) == 0 ? -1 : 1))).ToArray();

    private static readonly int[] _cubeTriangles =
    {
        0, 2, 3, 0, 3, 1, // z-
        4, 5, 7, 4, 7, 6, // z+
        0, 1, 5, 0, 5, 4, // y-
        2, 6, 7, 2, 7, 3, // y+
        0, 4, 6, 0, 6, 2, // x-
        1, 3, 7, 1, 7, 5, // x+
    };

    private static readonly Vector3d[] _octahedron =
    {
        new(1, 0, 0), new(-1, 0, 0), new(0, 1, 0), new(0, -1, 0), new(0, 0, 1), new(0, 0, -1),
    };

    private static readonly int[] _octahedronTriangles =
    {
        0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5,
    };

    [Fact]
    public void A_cube_mesh_fills_as_the_box_rule_fills_its_box()
    {
        // Cell centres on the lattice's diagonals lie in the planes of the faces' diagonals: a ray count would stumble there.
        var mesh = BodyLattice.Mesh(_cube, _cubeTriangles, 0.25);
        var box = BodyLattice.Box(new Vector3d(0.3, -0.2, 0.1), new Vector3d(2, 2, 2), Rotation3d.Identity, 0.25);
        Assert.Equal(box.Length, mesh.Length);
        for (var k = 0; k < box.Length; k++)
        {
            Assert.True((box[k] - mesh[k]).Length < 1e-15, $"cell {k}: {mesh[k]} against {box[k]}");
        }

        Assert.Equal(8.0, BodyLattice.MeshVolume(_cube, _cubeTriangles), 12);
    }

    [Fact]
    public void An_octahedron_holds_exactly_the_cell_centres_inside_it_whichever_way_it_faces()
    {
        // Inside |x| + |y| + |z| < 1, an independent test. Centres are odd multiples of h/2 = 0.05, and their sums never 1.
        var expected = BodyLattice.Box(Vector3d.Zero, new Vector3d(2, 2, 2), Rotation3d.Identity, 0.1)
            .Where(p => Math.Abs(p.X) + Math.Abs(p.Y) + Math.Abs(p.Z) < 1).ToArray();
        Assert.Equal(expected, BodyLattice.Mesh(_octahedron, _octahedronTriangles, 0.1));
        var inward = _octahedronTriangles.ToArray();
        for (var t = 0; t < inward.Length; t += 3)
        {
            (inward[t + 1], inward[t + 2]) = (inward[t + 2], inward[t + 1]);
        }

        Assert.Equal(expected, BodyLattice.Mesh(_octahedron, inward, 0.1));
        Assert.Equal(4.0 / 3.0, BodyLattice.MeshVolume(_octahedron, inward), 12);
        Assert.InRange(expected.Length * 1e-3, 0.98 * 4 / 3, 4.0 / 3);
    }

    [Fact]
    public void Meshes_that_cannot_be_filled_are_refused_with_the_reason()
    {
        // At spacing 0.9 the octahedron's lattice is 2 x 2 x 2 cells centred at (+-0.45, +-0.45, +-0.45), all outside.
        var open = _cubeTriangles.Take(33).ToArray();
        Assert.Contains("is not closed: its edge from vertex", Assert.Throws<ArgumentException>(() => BodyLattice.Mesh(_cube, open, 0.25)).Message);
        var missing = _cubeTriangles.ToArray();
        missing[4] = 8;
        Assert.Contains("Triangle 1 names vertex 8", Assert.Throws<ArgumentException>(() => BodyLattice.Mesh(_cube, missing, 0.25)).Message);
        var infinite = _cube.ToArray();
        infinite[2] = new Vector3d(double.NaN, 0, 0);
        Assert.Contains("Vertex 2 is", Assert.Throws<ArgumentException>(() => BodyLattice.MeshVolume(infinite, _cubeTriangles)).Message);
        Assert.Contains("give a smaller spacing", Assert.Throws<ArgumentException>(() => BodyLattice.Mesh(_octahedron, _octahedronTriangles, 0.9)).Message);
    }
}
