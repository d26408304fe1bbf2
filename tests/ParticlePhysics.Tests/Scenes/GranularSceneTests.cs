using System;
using System.Globalization;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenes;

namespace ParticlePhysics.Tests.Scenes;

/// <summary>The scene kind <c>granular</c>: a block filled by the lattice rule, grains that roll with their friction.</summary>
public class GranularSceneTests
{
    private readonly Xunit.Abstractions.ITestOutputHelper _output;

    public GranularSceneTests(Xunit.Abstractions.ITestOutputHelper output)
    {
        _output = output;
    }

    [Fact]
    public void A_block_fills_from_min_to_max_with_a_mass_of_density_h_cubed_each()
    {
        var scene = Scene.Parse("""
            { "objects": [{ "type": "granular", "box": { "min": [0, 1, 0], "max": [0.3, 1.2, 0.1] }, "spacing": 0.1, "density": 1600, "radius": 0.04 }] }
            """);
        var world = scene.Build();

        Assert.Equal(3 * 2 * 1, world.Count);
        for (var i = 0; i < world.Count; i++)
        {
            var expected = new Vector3d(0.05 + (0.1 * (i % 3)), 1.05 + (0.1 * (i / 3)), 0.05);
            Assert.True((world.GetPosition(i) - expected).Length < 1e-15, $"grain {i} at {world.GetPosition(i)}, not {expected}");
            Assert.Equal(1.6, world.GetMass(i), 14);
            Assert.Equal(0.04, world.GetRadius(i));
        }

        var description = scene.Describe();
        Assert.Contains("rigid bodies: 0, soft bodies: 0, grains: 6", description, StringComparison.Ordinal);
        Assert.Contains("particle collisions: off (but solids collide with every particle with a radius)", description, StringComparison.Ordinal);
    }

    [Fact]
    public void A_scene_with_sleep_puts_a_grain_at_rest_to_sleep_after_the_time_it_gives()
    {
        var scene = Scene.Parse("""
            { "sleep": { "speed": 0.05, "time": 0.25 },
              "objects": [{ "type": "granular", "box": { "min": [0, 0, 0], "max": [0.1, 0.1, 0.1] }, "spacing": 0.1 }],
              "colliders": [{ "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0] }] }
            """);
        var world = scene.Build();
        Assert.Equal(0.05, world.SleepSpeed);
        Assert.Equal(0.25, world.SleepTime);
        Assert.Contains("sleep: below 0.05 m/s for 0.25 s", scene.Describe(), StringComparison.Ordinal);
        var xpbd = new Xpbd(10);
        var steps = 0;
        while (world.SleepingCount == 0 && steps < 60)
        {
            world.Step(xpbd, 1.0 / 60);
            steps++;
        }

        // It rests on the ground from the start, so it is calm from the first step and sleeps after 0.25 s of steps.
        Assert.InRange(steps, 15, 17);
    }

    [Theory]
    [InlineData(0.0)]
    [InlineData(0.1)]
    public void A_grain_rolls_down_a_slope_at_five_sevenths_of_g_sin_theta_less_its_rolling_friction(double rolling)
    {
        // A solid sphere rolling without slipping: m a = m g sin(theta) - f and (2/5) m r a = f r - mu_r N r give
        // a = (5/7) g (sin(theta) - mu_r cos(theta)); it does not slip while tan(theta) < (7/2) mu.
        const double theta = 20 * Math.PI / 180;
        var normal = new Vector3d(Math.Sin(theta), Math.Cos(theta), 0);
        var start = 0.05 * normal;
        var scene = Scene.Parse(string.Format(CultureInfo.InvariantCulture, """
            {{ "duration": 1, "objects": [{{ "type": "granular", "spacing": 0.1, "friction": 0.5, "rollingFriction": {0:R},
                "box": {{ "min": [{1:R}, {2:R}, -0.05], "max": [{3:R}, {4:R}, 0.05] }} }}],
              "colliders": [{{ "type": "plane", "point": [0, 0, 0], "normal": [{5:R}, {6:R}, 0], "friction": 0.5 }}] }}
            """, rolling, start.X - 0.05, start.Y - 0.05, start.X + 0.05, start.Y + 0.05, normal.X, normal.Y));
        var world = scene.Build();
        var integrator = IntegratorCatalog.Create(scene.Settings.Integrator, scene.Settings.Tolerance, scene.Settings.Substeps);
        for (var step = 0; step < 60; step++)
        {
            world.Step(integrator, scene.Settings.TimeStep);
        }

        var travel = (world.GetPosition(0) - start).Length;
        var expected = 0.5 * (5.0 / 7.0) * 9.81 * (Math.Sin(theta) - (rolling * Math.Cos(theta)));
        _output.WriteLine($"mu_r = {rolling}: rolled {travel:F4} m in 1 s; (5/14) g (sin - mu_r cos) = {expected:F4} m");
        Assert.True(Math.Abs(travel - expected) < 0.01 * expected, $"{travel} m against {expected} m");
    }
}
