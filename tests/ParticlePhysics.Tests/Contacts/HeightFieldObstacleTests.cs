using System;
using System.Linq;
using ParticlePhysics.Contacts;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Tests.Support;
using Xunit.Abstractions;

namespace ParticlePhysics.Tests.Contacts;

/// <summary>
/// Height fields against exact answers: a slide down a planar incline of cells stops after v0^2 / (2 g (mu cos - sin))
/// when mu &gt; tan(theta) and accelerates at g (sin - mu cos) when mu &lt; tan(theta); a ball bounces on it as on a plane.
/// </summary>
[Collection(AllocationMeasurements.Name)]
public class HeightFieldObstacleTests(ITestOutputHelper output)
{
    private const double G = 9.81;

    [Theory]
    [InlineData("rk4")]
    [InlineData("velocity-verlet")]
    [InlineData("semi-implicit-euler")]
    public void A_slide_down_a_planar_height_field_with_mu_above_tan_theta_stops_after_the_exact_distance(string integrator)
    {
        const double mu = 0.6;
        const double v0 = 3.0;
        var theta = 20 * Math.PI / 180;
        var world = Incline(theta, mu, v0, out var down);
        FrictionTests.StepFor(world, integrator, 1e-3, 3.0);
        var exact = v0 * v0 / (2 * G * ((mu * Math.Cos(theta)) - Math.Sin(theta)));
        var slid = Vector3d.Dot(world.GetPosition(0) - Start(theta), down);
        var error = Math.Abs(slid - exact) / exact;
        output.WriteLine($"{integrator}: stopped after {slid:R} m, exactly {exact:R} m: {error:E2} relative");
        Assert.True(error < 1e-6, $"stopped after {slid:R}, exactly {exact:R}");
        Assert.True(world.GetVelocity(0).Length < 1e-9, $"still moving at {world.GetVelocity(0)}");
    }

    [Theory]
    [InlineData("rk4")]
    [InlineData("velocity-verlet")]
    public void A_slide_down_a_planar_height_field_with_mu_below_tan_theta_accelerates_at_g_sin_minus_mu_cos(string integrator)
    {
        const double mu = 0.2;
        const double v0 = 1.0;
        const double duration = 2.0;
        var theta = 20 * Math.PI / 180;
        var world = Incline(theta, mu, v0, out var down);
        FrictionTests.StepFor(world, integrator, 1e-3, duration);
        var a = G * (Math.Sin(theta) - (mu * Math.Cos(theta)));
        var speed = Vector3d.Dot(world.GetVelocity(0), down);
        var slid = Vector3d.Dot(world.GetPosition(0) - Start(theta), down);
        var error = Math.Abs(speed - (v0 + (a * duration))) / (v0 + (a * duration));
        output.WriteLine($"{integrator}: {speed:R} m/s, exactly {v0 + (a * duration):R}: {error:E2} relative");
        Assert.True(error < 1e-9, $"speed {speed:R}");
        Assert.True(Math.Abs(slid - ((v0 * duration) + (0.5 * a * duration * duration))) < 1e-9, $"slid {slid:R}");
        Assert.True((world.GetVelocity(0) - (speed * down)).Length < 1e-12, "off the line of steepest descent");
    }

    [Fact]
    public void A_ball_bounces_on_a_flat_height_field_to_the_planes_apexes()
    {
        var scenario = new ParticlePhysics.Scenarios.BouncingBallScenario();
        var heights = new double[5, 7];
        var field = new HeightFieldObstacle(new Vector3d(-2.3, 0, -1.7), 0.7, 0.9, heights, restitution: scenario.Restitution);
        var run = Bounces.Record(scenario, "rk4", 0.001, 5, contacts =>
        {
            contacts.Remove(contacts.Obstacles[0]);
            contacts.Add(field);
        });
        for (var n = 1; n <= 20; n++)
        {
            Assert.True(Math.Abs(run.Apexes[n - 1] - scenario.ApexHeight(n)) < 1e-12 * scenario.ApexHeight(n), $"apex {n}");
        }
    }

    [Fact]
    public void A_particle_below_the_surface_is_pushed_up_out_of_the_ground()
    {
        var heights = new double[,] { { 0, 0.1 }, { 0.2, 0.3 } };
        var field = new HeightFieldObstacle(Vector3d.Zero, 1, 1, heights);
        Assert.True(field.SignedDistance(new Vector3d(0.5, -0.5, 0.5), out var normal) < -0.5);
        Assert.True(normal.Y > 0.9);
        Assert.True(field.SignedDistance(new Vector3d(0.25, 1, 0.25), out _) > 0.5);

        // Beside a flat grid, below its rim, is outside: at the distance from the rim.
        field = new HeightFieldObstacle(Vector3d.Zero, 1, 1, new double[2, 2]);
        Assert.Equal(Math.Sqrt(0.25 + 0.04), field.SignedDistance(new Vector3d(-0.5, -0.2, 0.5), out _), 14);
        Assert.Equal(Math.Sqrt(0.25 + 0.09), field.SignedDistance(new Vector3d(0.5, -0.3, -0.5), out _), 14);
    }

    [Theory]
    [InlineData(0.0, 1.0, "dx")]
    [InlineData(1.0, double.NaN, "dz")]
    public void A_height_field_that_is_not_allowed_is_refused_with_the_value_named(double dx, double dz, string named)
    {
        var error = Assert.ThrowsAny<ArgumentException>(() => new HeightFieldObstacle(Vector3d.Zero, dx, dz, new double[2, 2]));
        Assert.Contains(named, error.Message);
        error = Assert.ThrowsAny<ArgumentException>(() => new HeightFieldObstacle(Vector3d.Zero, 1, 1, new double[1, 3]));
        Assert.Contains("2 rows", error.Message);
        error = Assert.ThrowsAny<ArgumentException>(() => new HeightFieldObstacle(Vector3d.Zero, 1, 1, new double[,] { { 0, 1 }, { double.PositiveInfinity, 0 } }));
        Assert.Contains("heights[1, 0]", error.Message);
    }

    /// <summary>Where the slides start: on the surface of a field falling along +x, inside a cell.</summary>
    private static Vector3d Start(double theta) => new(1.3, -1.3 * Math.Tan(theta), 1.1);

    /// <summary>A point particle on a planar field falling along +x at angle theta, launched down it at v0.</summary>
    private static ParticleWorld Incline(double theta, double mu, double v0, out Vector3d down)
    {
        const int columns = 41;
        const double dx = 0.5;
        var heights = new double[4, columns];
        for (var r = 0; r < 4; r++)
        {
            for (var c = 0; c < columns; c++)
            {
                heights[r, c] = -c * dx * Math.Tan(theta);
            }
        }

        var field = new HeightFieldObstacle(Vector3d.Zero, dx, 0.8, heights, friction: mu);
        down = new Vector3d(Math.Cos(theta), -Math.Sin(theta), 0);
        var world = new ParticleWorld();
        world.AddParticle(Start(theta), v0 * down, 1);
        world.AddForce(Gravity.Down(G));
        var contacts = new ContactSet();
        contacts.Add(field);
        world.AddConstraints(contacts);
        return world;
    }
}
