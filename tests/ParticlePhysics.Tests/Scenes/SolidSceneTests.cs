using System;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenes;

namespace ParticlePhysics.Tests.Scenes;

/// <summary>The scene kinds <c>rigid</c> and <c>soft</c>: bodies filled by the lattice rule, their motion and materials, their contacts.</summary>
public class SolidSceneTests
{
    private readonly Xunit.Abstractions.ITestOutputHelper _output;

    public SolidSceneTests(Xunit.Abstractions.ITestOutputHelper output)
    {
        _output = output;
    }

    [Fact]
    public void A_box_fills_by_the_lattice_rule_with_its_mass_shared_and_a_mesh_by_its_inside()
    {
        var scene = Scene.Parse("""
            { "objects": [
                { "type": "rigid", "box": { "center": [0, 1, 0], "size": [0.4, 0.2, 0.25] }, "spacing": 0.1, "mass": 2.4 },
                { "type": "soft", "mesh": { "vertices": [[0,0,0],[1,0,0],[0,1,0],[1,1,0],[0,0,1],[1,0,1],[0,1,1],[1,1,1]],
                  "triangles": [[0,2,3],[0,3,1],[4,5,7],[4,7,6],[0,1,5],[0,5,4],[2,6,7],[2,7,3],[0,4,6],[0,6,2],[1,3,7],[1,7,5]] },
                  "spacing": 0.5, "density": 1000, "stiffness": 0.3 } ] }
            """);
        var world = scene.Build();

        // round(0.4 / 0.1) x round(0.2 / 0.1) x round(0.25 / 0.1) = 4 x 2 x 3 (2.5 rounds up), then the cube's 2 x 2 x 2.
        Assert.Equal(24 + 8, world.Count);
        foreach (var (i, expected) in new[] { (0, new Vector3d(-0.15, 0.95, -0.075)), (23, new Vector3d(0.15, 1.05, 0.125)), (24, new Vector3d(0.25, 0.25, 0.25)), (31, new Vector3d(0.75, 0.75, 0.75)) })
        {
            Assert.True((world.GetPosition(i) - expected).Length < 1e-15, $"particle {i} at {world.GetPosition(i)}, not {expected}");
        }

        for (var i = 0; i < world.Count; i++)
        {
            Assert.Equal(i < 24 ? 0.1 : 125.0, world.GetMass(i), 12);
            Assert.Equal(i < 24 ? 0.05 : 0.25, world.GetRadius(i));
        }

        var description = scene.Describe();
        Assert.Contains("rigid bodies: 1, soft bodies: 1", description, StringComparison.Ordinal);
        Assert.Contains("particle collisions: off (but solids collide with every particle with a radius)", description, StringComparison.Ordinal);
    }

    [Fact]
    public void A_box_launched_with_its_own_friction_stops_after_v0_squared_over_2_mu_g_with_the_mean_mu()
    {
        // mu = (0.6 + 0.2) / 2 = 0.4 between the box and the ground: 4 / (2 0.4 9.81) = 0.5097 m.
        var scene = Scene.Parse("""
            { "duration": 1.5, "objects": [
                { "type": "rigid", "box": { "center": [0, 0.1, 0], "size": [0.2, 0.2, 0.2] }, "spacing": 0.1, "velocity": [2, 0, 0], "friction": 0.6 } ],
              "colliders": [{ "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "friction": 0.2 }] }
            """);
        var world = Run(scene);
        var travel = Centre(world, 0, world.Count).X;
        var expected = 4 / (2 * 0.4 * 9.81);
        _output.WriteLine($"the box stopped after {travel:F4} m; v0^2 / (2 mu g) = {expected:F4} m");
        Assert.True(Math.Abs(travel - expected) < 0.03 * expected, $"{travel} m against {expected} m");
        Assert.True(world.GetVelocity(0).Length < 1e-6);
    }

    [Fact]
    public void Solids_meet_each_other_and_loose_particles_while_loose_particles_pass_through_each_other()
    {
        // A box dropped onto a box rests on it, and a ball dropped onto the boxes rests in the dip between the four
        // particles of the top (0.05 sqrt 2 from each: sqrt(0.1^2 - 0.005) = 0.0707 m above them); a ball dropped onto a
        // ball on the ground passes through it, as the contract has particles do without particleCollisions. The boxes
        // need their friction: without it, a box of spheres resting sphere on sphere is balanced unstably, and slides off.
        var scene = Scene.Parse("""
            { "duration": 2, "objects": [
                { "type": "rigid", "box": { "center": [0, 0.1, 0], "size": [0.2, 0.2, 0.2] }, "spacing": 0.1, "friction": 0.5 },
                { "type": "rigid", "box": { "center": [0, 0.5, 0], "size": [0.2, 0.2, 0.2] }, "spacing": 0.1, "friction": 0.5 },
                { "type": "particles", "positions": [[0, 1, 0], [1, 0.05, 0], [1, 0.5, 0]], "radius": 0.05, "mass": 0.1 } ],
              "colliders": [{ "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "friction": 0.5 }] }
            """);
        var world = Run(scene);
        var top = Centre(world, 8, 8);
        _output.WriteLine($"upper box at y = {top.Y:F4} m, the ball on it at {world.GetPosition(16).Y:F4} m, the ball on the ball at {world.GetPosition(18).Y:F4} m");
        Assert.True(Math.Abs(top.Y - 0.3) < 0.003, $"upper box at {top.Y} m");
        Assert.True(Math.Abs(world.GetPosition(16).Y - (0.35 + Math.Sqrt(0.005))) < 0.003, $"the ball on the boxes at {world.GetPosition(16)} m");
        Assert.Equal(0.05, world.GetPosition(18).Y, 3);
    }

    [Fact]
    public void A_bodys_velocity_and_spin_set_its_particles_moving_rigidly()
    {
        var scene = Scene.Parse("""
            { "objects": [
                { "type": "soft", "box": { "center": [1, 2, 3], "size": [0.3, 0.2, 0.1] }, "spacing": 0.1,
                  "velocity": [1, 0, -1], "angularVelocity": [0, 0, 4] } ] }
            """);
        var world = scene.Build();
        var centre = new Vector3d(1, 2, 3);
        for (var i = 0; i < world.Count; i++)
        {
            var expected = new Vector3d(1, 0, -1) + Vector3d.Cross(new Vector3d(0, 0, 4), world.GetPosition(i) - centre);
            Assert.True((world.GetVelocity(i) - expected).Length < 1e-14, $"particle {i}: {world.GetVelocity(i)} against {expected}");
        }
    }

    [Fact]
    public void A_plastic_soft_box_dropped_on_the_ground_keeps_a_dent_where_an_elastic_one_springs_back()
    {
        // Two soft boxes of 4 x 4 x 4 particles, 20 cm, thrown down at 4 m/s onto the ground; the second is plastic
        // (yield 5 mm, creep 0.5). After 2 s the elastic one is back to its size, the plastic one lower.
        var scene = Scene.Parse("""
            { "duration": 2, "objects": [
                { "type": "soft", "box": { "center": [0, 0.2, 0], "size": [0.2, 0.2, 0.2] }, "spacing": 0.05, "stiffness": 0.2, "velocity": [0, -4, 0] },
                { "type": "soft", "box": { "center": [1, 0.2, 0], "size": [0.2, 0.2, 0.2] }, "spacing": 0.05, "stiffness": 0.2, "velocity": [0, -4, 0],
                  "plasticity": { "yield": 0.005, "creep": 0.5 } } ],
              "colliders": [{ "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "friction": 0.5 }] }
            """);
        var world = Run(scene);
        double Height(int first)
        {
            double low = double.MaxValue, high = double.MinValue;
            for (var i = first; i < first + 64; i++)
            {
                low = Math.Min(low, world.GetPosition(i).Y);
                high = Math.Max(high, world.GetPosition(i).Y);
            }

            return high - low;
        }

        var (elastic, plastic) = (Height(0), Height(64));
        _output.WriteLine($"after 2 s: elastic box {elastic:F4} m high, plastic box {plastic:F4} m (0.15 m between outer centres at rest)");
        Assert.True(Math.Abs(elastic - 0.15) < 0.003, $"the elastic box is {elastic} m high");
        Assert.True(plastic < 0.14, $"the plastic box is {plastic} m high: no dent");
    }

    private static ParticleWorld Run(Scene scene)
    {
        var world = scene.Build();
        var integrator = IntegratorCatalog.Create(scene.Settings.Integrator, scene.Settings.Tolerance, scene.Settings.Substeps);
        var steps = (int)Math.Round(scene.Settings.Duration / scene.Settings.TimeStep);
        for (var step = 0; step < steps; step++)
        {
            world.Step(integrator, scene.Settings.TimeStep);
        }

        return world;
    }

    private static Vector3d Centre(ParticleWorld world, int first, int count)
    {
        var sum = Vector3d.Zero;
        var mass = 0.0;
        for (var i = first; i < first + count; i++)
        {
            sum += world.GetMass(i) * world.GetPosition(i);
            mass += world.GetMass(i);
        }

        return sum / mass;
    }
}
