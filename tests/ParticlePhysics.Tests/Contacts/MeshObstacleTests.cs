using System;
using System.Linq;
using ParticlePhysics.Contacts;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Support;
using Xunit.Abstractions;

namespace ParticlePhysics.Tests.Contacts;

/// <summary>
/// Triangle mesh colliders against exact answers: the plane's bounces on a floor of two triangles, a closed box mesh's
/// distance against the box's own, a thin wall met at 1000 m/s, resting on a face, an edge and a vertex, a cloth on a
/// sphere of 1,280 facets.
/// </summary>
[Collection(AllocationMeasurements.Name)]
public class MeshObstacleTests(ITestOutputHelper output)
{
    [Theory]
    [InlineData(0.0, 0.0)] // inside a face
    [InlineData(0.3, 0.3)] // on the diagonal the two triangles share
    public void A_ball_on_a_two_triangle_floor_bounces_to_the_planes_apexes(double x, double z)
    {
        var scenario = new BouncingBallScenario();
        var floor = Floor(scenario.Restitution, 0.0, x - 40, z - 40, 80);
        var run = Bounces.Record(scenario, "rk4", BouncingBallScenario.DefaultTimeStep, BouncingBallScenario.DefaultDuration, contacts =>
        {
            contacts.Remove(contacts.Obstacles[0]);
            contacts.Add(floor);
        });
        Assert.True(run.Apexes.Count >= 20, $"only {run.Apexes.Count} bounces");
        var worst = 0.0;
        for (var n = 1; n <= 20; n++)
        {
            var exact = scenario.ApexHeight(n);
            worst = Math.Max(worst, Math.Abs(run.Apexes[n - 1] - exact) / exact);
        }

        output.WriteLine($"worst of 20 apexes: {worst:E2} relative");
        Assert.True(worst < 1e-6, $"worst apex error {worst:E2} relative");
    }

    [Theory]
    [InlineData(1e-3, 3e-3, 2e-2, 0.0, 0.0, 0.0)]
    [InlineData(0.3, 0.8, 0.5, 1.0, 2.0, -0.5)]
    public void A_closed_box_mesh_has_the_boxs_signed_distance_and_normal(double hx, double hy, double hz, double ax, double ay, double az)
    {
        var half = new Vector3d(hx, hy, hz);
        StandardMeshes.Box(half, out var vertices, out var triangles);
        var mesh = new MeshObstacle(vertices, triangles) { Position = new Vector3d(0.1, -0.2, 0.3) };
        var box = new BoxObstacle(mesh.Position, half);
        if (ax != 0.0)
        {
            mesh.SetOrientation(new Vector3d(ax, ay, az), new Vector3d(0, 1, 0));
            box.SetOrientation(new Vector3d(ax, ay, az), new Vector3d(0, 1, 0));
        }

        Assert.True(mesh.IsClosed);
        var random = new SeededRandom(31);
        var scale = 3 * Math.Max(hx, Math.Max(hy, hz));
        for (var k = 0; k < 4000; k++)
        {
            var p = mesh.Position + new Vector3d(random.Between(-scale, scale), random.Between(-scale, scale), random.Between(-scale, scale));
            var expected = box.SignedDistance(p, out var boxNormal);
            var actual = mesh.SignedDistance(p, out var meshNormal);
            Assert.True(Math.Abs(actual - expected) <= 1e-15 * (1 + scale), $"at {p}: {actual:R} vs {expected:R}");
            Assert.True((meshNormal - boxNormal).Length < 1e-9, $"at {p}: normal {meshNormal} vs {boxNormal}");
        }
    }

    [Fact]
    public void The_hierarchy_finds_the_nearest_of_all_triangles()
    {
        StandardMeshes.Icosphere(0.5, 4, out var vertices, out var triangles);
        var mesh = new MeshObstacle(vertices, triangles, twoSided: true);
        var random = new SeededRandom(7);
        for (var k = 0; k < 300; k++)
        {
            var p = new Vector3d(random.Between(-1, 1), random.Between(-1, 1), random.Between(-1, 1));
            var brute = double.PositiveInfinity;
            for (var t = 0; t < mesh.TriangleCount; t++)
            {
                mesh.GetTriangle(t, out var a, out var b, out var c);
                brute = Math.Min(brute, Math.Sqrt(TriangleGeometry.Closest(p, a, b, c, out _, out _)));
            }

            Assert.True(Math.Abs(mesh.SignedDistance(p, out _) - brute) < 1e-14, $"at {p}");
        }
    }

    [Theory]
    [InlineData(0.5)]
    [InlineData(0.0)]
    public void A_particle_at_1000_m_per_s_neither_enters_nor_passes_a_closed_box_mesh_5_cm_thick_at_60_Hz(double restitution)
    {
        const double radius = 0.01;
        StandardMeshes.Box(new Vector3d(0.025, 1, 1), out var vertices, out var triangles);
        var wall = new MeshObstacle(vertices, triangles, restitution: restitution);
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(-5, 0.2, 0.1), new Vector3d(1000, 0, 0), 1.0);
        world.SetRadius(0, radius);
        world.AddForce(Gravity.Down(9.81));
        var contacts = new ContactSet();
        contacts.Add(wall);
        world.AddConstraints(contacts);
        var stepper = new RungeKutta4();
        var impact = double.NaN;
        for (var step = 0; step < 30; step++)
        {
            world.Step(stepper, 1.0 / 60.0);
            if (double.IsNaN(impact) && contacts.ImpactCount > 0)
            {
                impact = contacts.Impacts[0].Time;
            }

            var p = world.GetPosition(0);
            Assert.True(p.X <= -0.025 - radius + 1e-9, $"step {step}: x = {p.X:R}");
            Assert.True(wall.SignedDistance(p, out _) >= radius - 1e-9, $"step {step}: inside");
        }

        output.WriteLine($"impact at {impact:R} s, {Math.Abs(impact - (4.965 / 1000)):E2} from 4.965 ms");

        // It meets the wall's face when it has flown 4.965 m at 1000 m/s.
        Assert.True(Math.Abs(impact - (4.965 / 1000)) < 1e-12, $"impact at {impact:R}");
    }

    [Theory]
    [InlineData("face")]
    [InlineData("edge")]
    [InlineData("vertex")]
    public void A_particle_rests_still_on_a_face_an_edge_and_a_vertex(string feature)
    {
        // A square pyramid (apex up, a vertex), a roof (ridge up, an edge), a box (top face): the particle starts at
        // rest touching the feature; gravity presses it along the normal there, which is vertical, and it stays.
        const double radius = 0.02;
        double[] vertices;
        int[] triangles;
        Vector3d top;
        switch (feature)
        {
            case "vertex":
                vertices = new double[] { -1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1, 0, 0.5, 0 };
                triangles = new[] { 0, 1, 2, 0, 2, 3, 0, 4, 1, 1, 4, 2, 2, 4, 3, 3, 4, 0 };
                top = new Vector3d(0, 0.5, 0);
                break;
            case "edge":
                vertices = new double[] { -1, 0, -1, 1, 0, -1, 0, 0.5, -1, -1, 0, 1, 1, 0, 1, 0, 0.5, 1 };
                triangles = new[] { 0, 2, 1, 3, 4, 5, 0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4, 0, 3, 5, 0, 5, 2 };
                top = new Vector3d(0, 0.5, 0.25);
                break;
            default:
                StandardMeshes.Box(new Vector3d(1, 0.25, 1), out vertices, out triangles);
                top = new Vector3d(0.125, 0.25, -0.375);
                break;
        }

        var mesh = new MeshObstacle(vertices, triangles, friction: 0.3);
        Assert.True(mesh.IsClosed);
        var world = new ParticleWorld();
        var start = top + new Vector3d(0, radius, 0);
        world.AddParticle(start, 1.0);
        world.SetRadius(0, radius);
        world.AddForce(Gravity.Down(9.81));
        var contacts = new ContactSet();
        contacts.Add(mesh);
        world.AddConstraints(contacts);
        foreach (var integrator in new[] { "rk4", "semi-implicit-euler", "xpbd" })
        {
            world.SetPosition(0, start);
            world.SetVelocity(0, Vector3d.Zero);
            var stepper = IntegratorCatalog.Create(integrator);
            for (var step = 0; step < 500; step++)
            {
                world.Step(stepper, 1e-3);
            }

            Assert.True((world.GetPosition(0) - start).Length < 1e-9, $"{integrator}: moved to {world.GetPosition(0)}");
            Assert.True(world.GetVelocity(0).Length < 1e-6, $"{integrator}: velocity {world.GetVelocity(0)}");
        }
    }

    [Theory]
    [InlineData(0.3, 0.5)]
    [InlineData(0.05, 8.0)]
    public void Friction_and_restitution_on_a_mesh_floor_follow_the_planes_path(double mu, double vx0)
    {
        var scenario = new BouncingBallScenario { Friction = mu, Vx0 = vx0 };
        var plane = scenario.Build();
        var mesh = scenario.Build();
        var contacts = mesh.Constraints.OfType<ContactSet>().Single();
        contacts.Remove(contacts.Obstacles[0]);
        contacts.Add(Floor(scenario.Restitution, mu, -20, -20, 60));
        var a = new RungeKutta4();
        var b = new RungeKutta4();
        for (var step = 1; step <= 4000; step++)
        {
            plane.Step(a, 0.001);
            mesh.Step(b, 0.001);
            Assert.True((plane.GetPosition(0) - mesh.GetPosition(0)).Length < 1e-9, $"step {step}: {mesh.GetPosition(0)} vs {plane.GetPosition(0)}");
            Assert.True((plane.GetVelocity(0) - mesh.GetVelocity(0)).Length < 1e-9, $"step {step}: velocity");
        }
    }

    [Fact]
    public void A_moving_mesh_floor_carries_a_resting_particle_as_a_moving_plane_does()
    {
        ParticleWorld Build(Obstacle ground)
        {
            ground.Velocity = new Vector3d(0.3, 0.5, 0);
            var world = new ParticleWorld();
            world.AddParticle(new Vector3d(1, 0.05, 1), 1.0);
            world.SetRadius(0, 0.05);
            world.AddForce(Gravity.Down(9.81));
            var contacts = new ContactSet();
            contacts.Add(ground);
            world.AddConstraints(contacts);
            return world;
        }

        var plane = Build(PlaneObstacle.Ground(0.0, 0.5));
        var mesh = Build(Floor(0.0, 0.5, -20, -20, 60));
        var a = new RungeKutta4();
        var b = new RungeKutta4();
        for (var step = 1; step <= 1000; step++)
        {
            plane.Step(a, 0.001);
            mesh.Step(b, 0.001);
            Assert.True((plane.GetPosition(0) - mesh.GetPosition(0)).Length < 1e-9, $"step {step}: {mesh.GetPosition(0)} vs {plane.GetPosition(0)}");
        }

        Assert.True(mesh.GetPosition(0).Y > 0.5, "the floor lifted the particle");
    }

    [Fact]
    public void A_cloth_dropped_on_a_1280_triangle_sphere_mesh_stays_outside_every_facet()
    {
        var scenario = new DrapeScenario();
        var cloth = scenario.BuildCloth();
        var world = cloth.System;
        var contacts = world.Constraints.OfType<ContactSet>().Single();
        contacts.Remove(contacts.Obstacles[0]);
        StandardMeshes.Icosphere(scenario.SphereRadius, 3, out var vertices, out var triangles);
        var sphere = new MeshObstacle(vertices, triangles, friction: scenario.Friction) { Position = scenario.SphereCenter };
        Assert.Equal(1280, sphere.TriangleCount);
        contacts.Add(sphere);
        var stepper = new RungeKutta4();
        var worst = double.PositiveInfinity;
        for (var step = 1; step <= 2000; step++)
        {
            world.Step(stepper, DrapeScenario.DefaultTimeStep);
            if (step % 50 == 0)
            {
                worst = Math.Min(worst, WorstFacetMargin(world, sphere, scenario.SphereCenter, scenario.Radius));
            }
        }

        // Every particle is no nearer the centre than the plane of the facet nearest it, plus its radius, less 1 mm.
        output.WriteLine($"least margin over the facet planes: {worst:R} m");
        Assert.True(worst >= -1e-3, $"a particle {-worst} m inside");
        var lowest = Enumerable.Range(0, world.Count).Min(i => world.GetPosition(i).Y);
        Assert.True(lowest < scenario.SphereY, $"the cloth does not hang around the sphere: lowest {lowest}");
    }

    [Fact]
    public void Stepping_a_cloth_on_a_mesh_allocates_nothing()
    {
        var scenario = new DrapeScenario();
        var world = scenario.Build();
        var contacts = world.Constraints.OfType<ContactSet>().Single();
        contacts.Remove(contacts.Obstacles[0]);
        StandardMeshes.Icosphere(scenario.SphereRadius, 3, out var vertices, out var triangles);
        contacts.Add(new MeshObstacle(vertices, triangles, friction: scenario.Friction) { Position = scenario.SphereCenter });
        var stepper = new RungeKutta4();
        StateMetrics.Run(world, stepper, 0.001, 300);
        Assert.Equal(0, ThreadAllocations.Measure(() => StateMetrics.Run(world, stepper, 0.001, 50)));
    }

    [Theory]
    [InlineData(new double[] { 0, 0, 0, 1, 0 }, new[] { 0, 1, 0 }, "vertices")]
    [InlineData(new double[] { 0, 0, 0, 1, 0, 0, 0, 1, 0 }, new[] { 0, 1, 3 }, "triangles[2]")]
    [InlineData(new double[] { 0, 0, 0, 1, 0, 0, 2, 0, 0 }, new[] { 0, 1, 2 }, "triangle 0")]
    [InlineData(new double[] { 0, 0, 0, 1, double.NaN, 0, 0, 1, 0 }, new[] { 0, 1, 2 }, "vertices[4]")]
    [InlineData(new double[] { 0, 0, 0, 1, 0, 0, 0, 1, 0 }, new[] { 0, 1 }, "triangles")]
    public void A_mesh_that_is_not_allowed_is_refused_with_the_value_named(double[] vertices, int[] triangles, string named)
    {
        var error = Assert.ThrowsAny<ArgumentException>(() => new MeshObstacle(vertices, triangles));
        Assert.Contains(named, error.Message);
    }

    /// <summary>The least, over the particles, of |p - c| - (h_t + r), t the facet nearest p and h_t its plane's distance from c.</summary>
    private static double WorstFacetMargin(ParticleWorld world, MeshObstacle sphere, Vector3d centre, double radius)
    {
        var worst = double.PositiveInfinity;
        for (var i = 0; i < world.Count; i++)
        {
            var p = world.GetPosition(i);
            var nearest = -1;
            var best = double.PositiveInfinity;
            for (var t = 0; t < sphere.TriangleCount; t++)
            {
                sphere.GetTriangle(t, out var a, out var b, out var c);
                var d = TriangleGeometry.Closest(p, a, b, c, out _, out _);
                if (d < best)
                {
                    best = d;
                    nearest = t;
                }
            }

            sphere.GetTriangle(nearest, out var a0, out var b0, out var c0);
            var n = Vector3d.Cross(b0 - a0, c0 - a0);
            var plane = Vector3d.Dot(a0 - centre, n / n.Length);
            worst = Math.Min(worst, (p - centre).Length - (plane + radius));
        }

        return worst;
    }

    /// <summary>A square floor of two triangles in y = 0 from (x, z) with side <paramref name="size"/>, its diagonal from (x, z).</summary>
    internal static MeshObstacle Floor(double restitution, double friction, double x, double z, double size)
    {
        var vertices = new[] { x, 0, z, x + size, 0, z, x + size, 0, z + size, x, 0, z + size };
        var triangles = new[] { 0, 2, 1, 0, 3, 2 };
        return new MeshObstacle(vertices, triangles, restitution: restitution, friction: friction);
    }
}
