using System;
using ParticlePhysics.Contacts;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Contacts;

/// <summary>
/// Raycasts, sphere casts and overlaps against exact answers (3-4-5 triangles, so that every distance is a short
/// decimal): on a sphere, a plane, a mesh, a height field and particles, to 1e-12 relative; and none allocates.
/// </summary>
[Collection(AllocationMeasurements.Name)]
public class QueryTests
{
    private static readonly Vector3d _sphereCentre = new(1, 2, 3);

    [Theory]
    [InlineData(0.0, 9.0)] // a ray 3 m off the centre of a ball of 5 m meets it 4 m before the centre's plane
    [InlineData(2.0, 9.0)] // a sphere of 2 m against a ball of 3 m: the same 3-4-5 triangle
    public void Casts_meet_a_sphere_at_the_exact_distance_and_point(double radius, double expected)
    {
        var contacts = new ContactSet();
        contacts.Add(new SphereObstacle(_sphereCentre, 5.0 - radius));
        var origin = _sphereCentre + new Vector3d(3, 0, -13);
        Assert.True(contacts.SphereCast(null, origin, new Vector3d(0, 0, 2), radius, double.PositiveInfinity, out var hit));
        Close(expected, hit.Distance);
        var normal = new Vector3d(0.6, 0, -0.8);
        Close(normal, hit.Normal);
        Close(_sphereCentre + ((5.0 - radius) * normal), hit.Point);
        Assert.Equal(0, hit.Obstacle);
        Assert.Equal(-1, hit.Particle);
    }

    [Theory]
    [InlineData("plane", 0.0)]
    [InlineData("mesh", 0.0)]
    [InlineData("plane", 0.5)]
    [InlineData("mesh", 0.5)]
    public void Casts_meet_a_plane_and_a_mesh_floor_at_the_exact_distance_and_point(string shape, double radius)
    {
        // From 7 m above the floor y = 1, slanting down at 4/5: the centre touches after (7 - r) / 0.8.
        var contacts = new ContactSet();
        contacts.Add(shape == "plane"
            ? new PlaneObstacle(new Vector3d(0, 1, 0), new Vector3d(0, 1, 0))
            : new MeshObstacle(new double[] { -10, 1, -10, 20, 1, -10, 20, 1, 20, -10, 1, 20 }, new[] { 0, 2, 1, 0, 3, 2 }));
        var origin = new Vector3d(1, 8, 2);
        Assert.True(contacts.SphereCast(null, origin, new Vector3d(3, -4, 0), radius, 100, out var hit));
        var expected = (7 - radius) / 0.8;
        Close(expected, hit.Distance);
        Close(new Vector3d(0, 1, 0), hit.Normal);
        Close(new Vector3d(1 + (0.6 * expected), 1, 2), hit.Point);
        Assert.Equal(shape == "mesh" ? 0 : -1, hit.Triangle); // (x, z) = (1 + 0.6 d, 2) has z < x: the triangle (0, 2, 1)
        Assert.False(contacts.Raycast(null, origin, new Vector3d(3, -4, 0), 8.7, out _)); // out of reach
    }

    [Fact]
    public void A_ray_meets_a_height_field_in_the_exact_cell_and_triangle()
    {
        // y = 0.5 x: a ray straight down at (1.3, ., 1.2) meets it at y = 0.65, in cell (1, 1), its first triangle.
        var heights = new double[4, 4];
        for (var r = 0; r < 4; r++)
        {
            for (var c = 0; c < 4; c++)
            {
                heights[r, c] = 0.5 * c;
            }
        }

        var contacts = new ContactSet();
        contacts.Add(new HeightFieldObstacle(Vector3d.Zero, 1, 1, heights));
        Assert.True(contacts.Raycast(null, new Vector3d(1.3, 5, 1.2), new Vector3d(0, -1, 0), 10, out var hit));
        Close(5 - 0.65, hit.Distance);
        Close(new Vector3d(1.3, 0.65, 1.2), hit.Point);
        Close(new Vector3d(-0.5, 1, 0) / Math.Sqrt(1.25), hit.Normal);
        Assert.Equal(2 * ((1 * 3) + 1), hit.Triangle);
    }

    [Theory]
    [InlineData(0.0, 0.3, 4.6)] // a ray 0.3 m off a particle of 0.5 m: 0.4 m short of its centre's plane
    [InlineData(0.5, 0.6, 4.2)] // a sphere of 0.5 m, 0.6 m off: the two radii make 1 m, 0.8 m short
    public void Casts_meet_a_particle_before_the_floor_behind_it(double radius, double offset, double expected)
    {
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(5, 0, 7), 1);
        world.AddParticle(Vector3d.Zero, 1);
        world.SetRadius(1, 0.5);
        var contacts = new ContactSet();
        contacts.Add(new PlaneObstacle(new Vector3d(0, 0, 3), new Vector3d(0, 0, -1)));
        var origin = new Vector3d(offset, 0, -5);
        Assert.True(contacts.SphereCast(world, origin, new Vector3d(0, 0, 1), radius, 100, out var hit));
        Assert.Equal(1, hit.Particle);
        Assert.Equal(-1, hit.Obstacle);
        Close(expected, hit.Distance);
        var normal = new Vector3d(offset, 0, -(5 - expected)) / (0.5 + radius);
        Close(normal, hit.Normal);
        Close(0.5 * normal, hit.Point);
    }

    [Fact]
    public void An_overlap_lists_the_obstacles_then_the_particles_it_touches()
    {
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(0.4, 1.3, 0), 1);
        world.AddParticle(new Vector3d(5, 5, 5), 1);
        world.SetRadius(0, 0.1);
        var contacts = new ContactSet();
        contacts.Add(new SphereObstacle(new Vector3d(0, 10, 0), 1));
        contacts.Add(new PlaneObstacle(new Vector3d(0, 1, 0), new Vector3d(0, 1, 0)));
        Span<QueryHit> hits = stackalloc QueryHit[4];
        var count = contacts.Overlap(world, new Vector3d(0, 1.2, 0), 0.5, hits);
        Assert.Equal(2, count);
        Assert.Equal(1, hits[0].Obstacle);
        Close(0.2, hits[0].Distance);
        Close(new Vector3d(0, 1, 0), hits[0].Point);
        Assert.Equal(0, hits[1].Particle);
        Assert.Equal(2, contacts.Overlap(world, new Vector3d(0, 1.2, 0), 0.5, hits.Slice(0, 1))); // counted all, though one fits
    }

    [Fact]
    public void Queries_allocate_nothing_and_refuse_bad_input()
    {
        StandardMeshes.Icosphere(1, 3, out var vertices, out var triangles);
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(0, 3, 0), 1);
        world.SetRadius(0, 0.2);
        var contacts = new ContactSet();
        contacts.Add(new MeshObstacle(vertices, triangles));
        contacts.Add(PlaneObstacle.Ground());
        var hits = new QueryHit[8];
        void Query()
        {
            _ = contacts.Raycast(world, new Vector3d(0.1, 5, 0.2), new Vector3d(0, -1, 0), 10, out _);
            _ = contacts.SphereCast(world, new Vector3d(0.1, 5, 0.2), new Vector3d(0, -1, 0.1), 0.3, 10, out _);
            _ = contacts.Overlap(world, new Vector3d(0, 1, 0), 0.5, hits);
        }

        Query();
        Assert.Equal(0, ThreadAllocations.Measure(Query));
        Assert.Contains("direction", Assert.ThrowsAny<ArgumentException>(() => contacts.Raycast(world, Vector3d.Zero, Vector3d.Zero, 1, out _)).Message);
        Assert.Contains("maxDistance", Assert.ThrowsAny<ArgumentException>(() => contacts.Raycast(world, Vector3d.Zero, new Vector3d(1, 0, 0), double.NaN, out _)).Message);
        Assert.Contains("radius", Assert.ThrowsAny<ArgumentException>(() => contacts.SphereCast(world, Vector3d.Zero, new Vector3d(1, 0, 0), -1, 1, out _)).Message);
    }

    private static void Close(double expected, double actual) =>
        Assert.True(Math.Abs(actual - expected) <= 1e-12 * Math.Abs(expected), $"{actual:R} vs {expected:R}");

    private static void Close(Vector3d expected, Vector3d actual) =>
        Assert.True((actual - expected).Length <= 1e-12 * Math.Max(expected.Length, 1e-300), $"{actual} vs {expected}");
}
