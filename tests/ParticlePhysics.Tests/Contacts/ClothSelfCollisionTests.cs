using System;
using ParticlePhysics.Cloth;
using ParticlePhysics.Contacts;
using ParticlePhysics.Integrators;
using ParticlePhysics.Tests.Cloth;
using ParticlePhysics.Tests.Support;
using Xunit.Abstractions;

namespace ParticlePhysics.Tests.Contacts;

/// <summary>A thin cloth that folds onto itself (issue 30): it lies on itself instead of passing through.</summary>
public class ClothSelfCollisionTests
{
    private const double Thickness = 0.01;
    private readonly ITestOutputHelper _output;

    public ClothSelfCollisionTests(ITestOutputHelper output) => _output = output;

    [Fact]
    public void A_long_strip_dropped_on_the_floor_piles_onto_itself_without_passing_through()
    {
        var drop = Strip(selfCollision: true);
        var (contacts, lowest) = Run(drop, 240);
        var (intersections, closest, height) = Inspect(drop);
        _output.WriteLine($"after 4 s: {intersections} intersecting triangle pairs, closest non-neighbours {closest * 1000:F2} mm apart, "
            + $"pile {height * 1000:F1} mm high (the strip 1 m long), {contacts} self-contacts projected, lowest particle at {lowest * 1000:F2} mm");

        Assert.True(height < 0.2, $"the strip should lie in a pile on the floor; its top is {height:F3} m up");
        Assert.True(contacts > 1000, $"the strip should have touched itself; {contacts} contacts");
        Assert.Equal(0, intersections);
        Assert.True(closest >= Thickness / 2, $"two non-neighbouring particles are {closest * 1000:F2} mm apart");
        Assert.True(lowest > 0.0, $"a particle went through the floor to {lowest:F4} m");
    }

    [Fact]
    public void A_cloth_falling_onto_a_sphere_folds_over_itself_without_passing_through()
    {
        var drop = Sheet();
        var (contacts, _) = Run(drop, 240);
        var (intersections, closest, height) = Inspect(drop);
        _output.WriteLine($"after 4 s: {intersections} intersecting triangle pairs, closest non-neighbours {closest * 1000:F2} mm apart, "
            + $"top {height * 1000:F1} mm up (the sphere's top at 300 mm), {contacts} self-contacts projected");

        Assert.True(contacts > 1000, $"the cloth should have folded onto itself; {contacts} contacts");
        Assert.Equal(0, intersections);
        Assert.True(closest >= Thickness / 2, $"two non-neighbouring particles are {closest * 1000:F2} mm apart");
    }

    [Fact]
    [Trait("Category", "Long")]
    public void Implicit_Euler_keeps_the_strip_off_itself_too()
    {
        const string integrator = "implicit-euler";
        var drop = Strip(selfCollision: true);
        var (contacts, _) = Run(drop, 2400, integrator, 1.0 / 600);
        var (intersections, closest, height) = Inspect(drop);
        _output.WriteLine($"{integrator}: {intersections} intersecting triangle pairs, closest non-neighbours {closest * 1000:F2} mm apart, pile {height * 1000:F1} mm high, {contacts} contacts");
        Assert.True(contacts > 100, $"the strip should have touched itself; {contacts} contacts");
        Assert.Equal(0, intersections);
        Assert.True(closest >= Thickness / 2, $"two non-neighbouring particles are {closest * 1000:F2} mm apart");
    }

    [Fact]
    public void Without_self_collision_the_same_strip_passes_through_itself()
    {
        // The oracle's check that the test above can fail: the same drop, particles still colliding with the floor.
        var drop = Strip(selfCollision: false);
        Run(drop, 240);
        var (intersections, closest, _) = Inspect(drop);
        _output.WriteLine($"without: {intersections} intersecting triangle pairs, closest non-neighbours {closest * 1000:F2} mm apart");
        Assert.True(intersections > 0 || closest < Thickness / 2);
    }

    [Fact]
    public void A_folding_strip_steps_without_allocating_and_repeats_bit_for_bit()
    {
        var drop = Strip(selfCollision: true);
        var xpbd = new Xpbd(10);
        var steps = 150;
        for (var s = 0; s < steps; s++)
        {
            drop.Cloth.System.Step(xpbd, 1.0 / 60);
        }

        var allocated = ThreadAllocations.Measure(() =>
        {
            for (var s = 0; s < 10; s++)
            {
                drop.Cloth.System.Step(xpbd, 1.0 / 60);
            }

            steps += 10; // Measure runs the work again when the runtime's count is spurious
        });
        Assert.True(drop.Self!.LastContactCount > 0, "the strip should be lying on itself");
        Assert.Equal(0, allocated);

        var again = Strip(selfCollision: true);
        Run(again, steps);
        Assert.Equal(StateMetrics.BitHash(drop.Cloth.System.State), StateMetrics.BitHash(again.Cloth.System.State));
    }

    [Fact]
    public void A_failed_step_leaves_the_cloth_and_the_set_as_they_were()
    {
        var drop = Strip(selfCollision: true);
        var xpbd = new Xpbd(10);
        for (var s = 0; s < 150; s++)
        {
            drop.Cloth.System.Step(xpbd, 1.0 / 60);
        }

        var contacts = drop.Self!.LastContactCount;
        var state = StateMetrics.BitHash(drop.Cloth.System.State);
        var failing = new FailingConstraints();
        drop.Cloth.System.AddConstraints(failing);
        Assert.Throws<InvalidOperationException>(() => drop.Cloth.System.Step(xpbd, 1.0 / 60));
        Assert.Equal(state, StateMetrics.BitHash(drop.Cloth.System.State));
        Assert.Equal(contacts, drop.Self.LastContactCount);
    }

    private sealed class FailingConstraints : IConstraintSet
    {
        public void Resolve(in ConstraintContext context) => throw new InvalidOperationException("fails");

        public void Project(in ConstraintContext context) => throw new InvalidOperationException("fails");

        public void SolveVelocities(in ConstraintContext context)
        {
        }
    }

    [Fact]
    public void The_cloth_fold_sample_scene_holds_its_golden_bits()
    {
        // The same hash is compared between Mono and CoreCLR by .ci/mono (tests/mono/RuntimeComparison.cs).
        var hash = SampleScenes.BitHashAfter("cloth-fold.json", 60);
        _output.WriteLine(hash);
        Assert.Equal("7A8D5EF5143E119C2440E83B5A0C81A1E9574F0748643393C7ABFE8B404E7E54", hash);
    }

    [Fact]
    public void Bad_input_is_refused_with_the_value_and_what_is_allowed()
    {
        var world = new ParticleWorld();
        for (var i = 0; i < 4; i++)
        {
            world.AddParticle(new Vector3d(i % 2, 0, i / 2), 1);
        }

        var thin = Assert.Throws<ArgumentOutOfRangeException>(() => new ClothSelfCollision(world, new[] { 0, 1, 2 }, 0.0));
        Assert.Contains("thickness", thin.Message);
        var missing = Assert.Throws<ArgumentOutOfRangeException>(() => new ClothSelfCollision(world, new[] { 0, 1, 7 }, 0.01));
        Assert.Contains("triangles[2]", missing.Message);
        var twice = Assert.Throws<ArgumentException>(() => new ClothSelfCollision(world, new[] { 0, 1, 1 }, 0.01));
        Assert.Contains("twice", twice.Message);
        Assert.Throws<ArgumentException>(() => new ClothSelfCollision(world, new[] { 0, 1 }, 0.01));

        var self = new ClothSelfCollision(world, new[] { 0, 1, 2, 1, 3, 2 }, 0.01);
        Assert.True(self.AreRestNeighbours(0, 0));
        Assert.False(self.AreRestNeighbours(3, 0)); // 0.71 m from the first triangle at rest
        Assert.Throws<ArgumentOutOfRangeException>(() => self.AreRestNeighbours(0, 2));
    }

    private sealed record Dropped(TriangleCloth Cloth, ClothSelfCollision? Self, int[] Triangles);

    private static Dropped Strip(bool selfCollision)
    {
        // 1 m long, 10 cm wide, 40 x 4 cells, hung upright with its foot 5 cm above the floor and a ripple of 5 mm.
        var (vertices, triangles) = ClothMeshes.Strip(40, 4, 0.025, 0.025);
        for (var v = 0; v < vertices.Length / 3; v++)
        {
            double along = vertices[3 * v], across = vertices[(3 * v) + 2];
            vertices[3 * v] = across;
            vertices[(3 * v) + 1] = 0.05 + along;
            vertices[(3 * v) + 2] = 0.005 * Math.Sin(2 * Math.PI * along / 0.3);
        }

        return Drop(vertices, triangles, selfCollision, PlaneObstacle.Ground(friction: 0.5));
    }

    private static Dropped Sheet()
    {
        // 80 cm square, 32 x 32 cells, level 10 cm above a sphere of radius 15 cm resting on the floor, off its centre.
        var (vertices, triangles) = ClothMeshes.Strip(32, 32, 0.025, 0.025);
        for (var v = 0; v < vertices.Length / 3; v++)
        {
            double a = vertices[3 * v], b = vertices[(3 * v) + 2];
            vertices[3 * v] = a - 0.35;
            vertices[(3 * v) + 1] = 0.4;
            vertices[(3 * v) + 2] = b - 0.42;
        }

        return Drop(vertices, triangles, true, PlaneObstacle.Ground(friction: 0.5), new SphereObstacle(new Vector3d(0, 0.15, 0), 0.15, friction: 0.5));
    }

    // A light, limp cloth (0.2 kg/m^2, Y = 1000 N/m, D = 1e-5 N m) whose particles collide with the obstacles at half
    // the thickness, with or without self-collision (added before the obstacles, so that they have the last word).
    private static Dropped Drop(double[] vertices, int[] triangles, bool selfCollision, params Obstacle[] obstacles)
    {
        var cloth = new MeshClothBuilder(new WeldedMesh(vertices, triangles)) { AreaDensity = 0.2, Modulus = 1000, Poisson = 0.3, BendingRigidity = 1e-5 }.Build();
        var world = cloth.System;
        for (var i = 0; i < world.Count; i++)
        {
            world.SetRadius(i, Thickness / 2);
        }

        var particleTriangles = cloth.Mesh.ParticleTriangles.ToArray();
        ClothSelfCollision? self = null;
        if (selfCollision)
        {
            self = new ClothSelfCollision(world, particleTriangles, Thickness);
            world.AddConstraints(self);
        }

        var contacts = new ContactSet();
        foreach (var obstacle in obstacles)
        {
            contacts.Add(obstacle);
        }

        world.AddConstraints(contacts);
        return new Dropped(cloth, self, particleTriangles);
    }

    private static (long Contacts, double Lowest) Run(Dropped drop, int steps, string integrator = "xpbd", double dt = 1.0 / 60)
    {
        var world = drop.Cloth.System;
        var xpbd = integrator == "xpbd" ? new Xpbd(10) : IntegratorCatalog.Create(integrator);
        long contacts = 0;
        var lowest = double.MaxValue;
        for (var s = 0; s < steps; s++)
        {
            world.Step(xpbd, dt);
            contacts += drop.Self?.LastContactCount ?? 0;
            for (var i = 0; i < world.Count; i++)
            {
                lowest = Math.Min(lowest, world.GetPosition(i).Y);
            }
        }

        return (contacts, lowest);
    }

    // Every pair of triangles that share no particle, every edge of each against the other's face; every pair of
    // particles that are not rest neighbours (no shared edge, and at least the thickness apart at rest).
    private static (int Intersections, double Closest, double Height) Inspect(Dropped drop)
    {
        var world = drop.Cloth.System;
        var t = drop.Triangles;
        var count = t.Length / 3;
        var intersections = 0;
        for (var i = 0; i < count; i++)
        {
            for (var j = i + 1; j < count; j++)
            {
                if (Shares(t, i, j))
                {
                    continue;
                }

                if (EdgesCross(world, t, i, j) || EdgesCross(world, t, j, i))
                {
                    intersections++;
                }
            }
        }

        var n = world.Count;
        var neighbour = new bool[n, n];
        for (var k = 0; k < t.Length; k += 3)
        {
            for (var e = 0; e < 3; e++)
            {
                neighbour[t[k + e], t[k + ((e + 1) % 3)]] = neighbour[t[k + ((e + 1) % 3)], t[k + e]] = true;
            }
        }

        var closest = double.MaxValue;
        var height = 0.0;
        for (var a = 0; a < n; a++)
        {
            height = Math.Max(height, world.GetPosition(a).Y);
            for (var b = a + 1; b < n; b++)
            {
                var rest = (drop.Cloth.Mesh.ParticlePosition(a) - drop.Cloth.Mesh.ParticlePosition(b)).Length;
                if (neighbour[a, b] || rest < Thickness)
                {
                    continue;
                }

                closest = Math.Min(closest, (world.GetPosition(a) - world.GetPosition(b)).Length);
            }
        }

        return (intersections, closest, height);
    }

    private static bool Shares(int[] t, int i, int j)
    {
        for (var a = 0; a < 3; a++)
        {
            for (var b = 0; b < 3; b++)
            {
                if (t[(3 * i) + a] == t[(3 * j) + b])
                {
                    return true;
                }
            }
        }

        return false;
    }

    private static bool EdgesCross(ParticleWorld world, int[] t, int edges, int face)
    {
        Vector3d a = world.GetPosition(t[3 * face]), b = world.GetPosition(t[(3 * face) + 1]), c = world.GetPosition(t[(3 * face) + 2]);
        for (var e = 0; e < 3; e++)
        {
            var p = world.GetPosition(t[(3 * edges) + e]);
            var q = world.GetPosition(t[(3 * edges) + ((e + 1) % 3)]);
            if (SegmentCrossesTriangle(p, q, a, b, c))
            {
                return true;
            }
        }

        return false;
    }

    // The segment pq meets the triangle abc: p and q on opposite sides of its plane, and the crossing point inside it
    // (signed volumes, Möller-Trumbore's test in another form).
    private static bool SegmentCrossesTriangle(Vector3d p, Vector3d q, Vector3d a, Vector3d b, Vector3d c)
    {
        var n = Vector3d.Cross(b - a, c - a);
        double dp = Vector3d.Dot(p - a, n), dq = Vector3d.Dot(q - a, n);
        if (dp * dq > 0 || (dp == 0 && dq == 0))
        {
            return false;
        }

        var x = p + ((dp / (dp - dq)) * (q - p));
        var u = Vector3d.Dot(Vector3d.Cross(b - a, x - a), n);
        var v = Vector3d.Dot(Vector3d.Cross(c - b, x - b), n);
        var w = Vector3d.Dot(Vector3d.Cross(a - c, x - c), n);
        return (u >= 0 && v >= 0 && w >= 0) || (u <= 0 && v <= 0 && w <= 0);
    }
}
