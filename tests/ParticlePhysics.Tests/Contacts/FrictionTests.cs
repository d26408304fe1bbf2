using System;
using System.Linq;
using ParticlePhysics.Contacts;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Tests.Contacts;

/// <summary>Coulomb friction while resting: a slide stops after v0^2 / (2 mu g); a particle on an incline sticks exactly when tan(theta) &lt;= mu.</summary>
public class FrictionTests
{
    private const double G = 9.81;

    public static TheoryData<string, double> IntegratorsAndSteps()
    {
        var data = new TheoryData<string, double>();
        foreach (var name in IntegratorCatalog.Names)
        {
            if (IntegratorCatalog.IsPositionBased(name))
            {
                continue; // xpbd's contacts are first order in the substep (below)
            }

            data.Add(name, 0.001);
            data.Add(name, 1.0 / 60.0);
        }

        return data;
    }

    [Theory]
    [MemberData(nameof(IntegratorsAndSteps))]
    public void A_sliding_particle_stops_after_v0_squared_over_2_mu_g(string integrator, double dt)
    {
        const double v0 = 3, mu = 0.5;
        var world = Ground(mu, new Vector3d(0, 0, 0), new Vector3d(v0, 0, 0));
        StepFor(world, integrator, dt, 2.0);
        var expected = v0 * v0 / (2 * mu * G);
        Assert.True(Math.Abs(world.GetPosition(0).X - expected) < 1e-12, $"stopped at {world.GetPosition(0).X:R}, exact {expected:R}");
        Assert.Equal(Vector3d.Zero, world.GetVelocity(0));
        Assert.Equal(0.0, world.GetPosition(0).Y);
    }

    [Theory]
    [InlineData(0.001, 5e-4)]
    [InlineData(1.0 / 60.0, 5e-3)]
    public void Under_xpbd_a_slide_stops_near_v0_squared_over_2_mu_g(double dt, double tolerance)
    {
        const double v0 = 3, mu = 0.5;
        var world = Ground(mu, Vector3d.Zero, new Vector3d(v0, 0, 0));
        StepFor(world, "xpbd", dt, 2.0);
        var expected = v0 * v0 / (2 * mu * G);
        Assert.True(Math.Abs(world.GetPosition(0).X - expected) < tolerance * expected, $"stopped at {world.GetPosition(0).X:R}, exact {expected:R}");
        Assert.Equal(Vector3d.Zero, world.GetVelocity(0));
    }

    [Fact]
    public void The_slide_follows_the_exact_deceleration_at_every_step()
    {
        const double v0 = 2, mu = 0.25, dt = 0.01;
        var world = Ground(mu, Vector3d.Zero, new Vector3d(0, 0, v0));
        var rk4 = new RungeKutta4();
        for (var step = 1; step <= 100; step++)
        {
            world.Step(rk4, dt);
            var t = Math.Min(step * dt, v0 / (mu * G));
            Assert.Equal((v0 * t) - (0.5 * mu * G * t * t), world.GetPosition(0).Z, 12);
            Assert.Equal(Math.Max(0, v0 - (mu * G * step * dt)), world.GetVelocity(0).Z, 12);
        }
    }

    [Theory]
    [InlineData(0.5, -0.5, true)]
    [InlineData(0.5, -0.01, true)]
    [InlineData(0.5, 0.01, false)]
    [InlineData(0.5, 1.0, false)]
    [InlineData(1.0, -1.0, true)]
    [InlineData(1.0, 2.0, false)]
    [InlineData(0.0, 5.0, false)]
    public void A_particle_on_an_incline_sticks_exactly_when_tan_theta_is_at_most_mu(double mu, double degreesFromLimit, bool sticks)
    {
        var theta = Math.Atan(mu) + (degreesFromLimit * Math.PI / 180);
        var normal = new Vector3d(-Math.Sin(theta), Math.Cos(theta), 0);
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(1, 2, 3), 1);
        world.AddForce(Gravity.Down(G));
        var contacts = new ContactSet();
        contacts.Add(new PlaneObstacle(new Vector3d(1, 2, 3), normal, 0, mu));
        world.AddConstraints(contacts);
        StepFor(world, "rk4", 1.0 / 60.0, 2.0);
        var moved = (world.GetPosition(0) - new Vector3d(1, 2, 3)).Length;
        var expected = sticks ? 0 : 0.5 * G * (Math.Sin(theta) - (mu * Math.Cos(theta))) * 2.0 * 2.0;
        Assert.True(Math.Abs(moved - expected) < 1e-9 * Math.Max(1, expected), $"moved {moved:R}, expected {expected:R}");
    }

    public static TheoryData<string, double> EveryIntegratorAndStep()
    {
        var data = new TheoryData<string, double>();
        foreach (var name in IntegratorCatalog.Names)
        {
            data.Add(name, 0.001);
            data.Add(name, 1.0 / 60.0);
        }

        return data;
    }

    [Theory]
    [MemberData(nameof(EveryIntegratorAndStep))]
    public void Under_every_integrator_a_particle_at_rest_on_an_incline_within_the_friction_cone_stays_exactly_put(string integrator, double dt)
    {
        // Issue 27, item 5: on 30 degrees with mu = 0.6 (> tan 30 = 0.577) at 60 Hz the Euler integrators moved 0.0409 m
        // in 1 s, g sin(theta) dt^2 / 2 a step: the correction took a t^2 / 2 off, what an exact integrator adds.
        var theta = 30 * Math.PI / 180;
        var start = new Vector3d(1, 2, 3);
        var world = new ParticleWorld();
        world.AddParticle(start, 1);
        world.AddForce(Gravity.Down(G));
        var contacts = new ContactSet();
        contacts.Add(new PlaneObstacle(start, new Vector3d(-Math.Sin(theta), Math.Cos(theta), 0), 0, 0.6));
        world.AddConstraints(contacts);
        StepFor(world, integrator, dt, 1.0);
        Assert.True((world.GetPosition(0) - start).Length < 1e-12, $"moved {(world.GetPosition(0) - start).Length:R} m to {world.GetPosition(0)}");
        Assert.True(world.GetVelocity(0).Length < 1e-12, $"moving at {world.GetVelocity(0)}");

        // Thrown up the slope, it stops and then stays where it stopped.
        var up = new Vector3d(Math.Cos(theta), Math.Sin(theta), 0);
        world.SetVelocity(0, 2.0 * up);
        StepFor(world, integrator, dt, 0.5);
        var stopped = world.GetPosition(0);
        Assert.True(Vector3d.Dot(stopped - start, up) > 0.1, $"{integrator}: stopped at {stopped}");
        StepFor(world, integrator, dt, 1.0);
        Assert.True((world.GetPosition(0) - stopped).Length < 1e-12, $"crept {(world.GetPosition(0) - stopped).Length:R} m after stopping");
    }

    [Fact]
    public void A_particle_pushed_up_an_incline_stops_and_slides_back_when_tan_theta_exceeds_mu()
    {
        const double mu = 0.2;
        var theta = 30 * Math.PI / 180;
        var up = new Vector3d(Math.Cos(theta), Math.Sin(theta), 0);
        var world = new ParticleWorld();
        world.AddParticle(Vector3d.Zero, 2.0 * up, 1);
        world.AddForce(Gravity.Down(G));
        var contacts = new ContactSet();
        contacts.Add(new PlaneObstacle(Vector3d.Zero, new Vector3d(-Math.Sin(theta), Math.Cos(theta), 0), 0, mu));
        world.AddConstraints(contacts);
        StepFor(world, "rk4", 0.01, 1.0);

        // Up at g (sin + mu cos) until it stops, then down at g (sin - mu cos).
        var upDeceleration = G * (Math.Sin(theta) + (mu * Math.Cos(theta)));
        var stop = 2.0 / upDeceleration;
        var down = G * (Math.Sin(theta) - (mu * Math.Cos(theta)));
        var along = (2.0 * stop) - (0.5 * upDeceleration * stop * stop) - (0.5 * down * (1.0 - stop) * (1.0 - stop));
        Assert.Equal(along, Vector3d.Dot(world.GetPosition(0), up), 9);
        Assert.Equal(-down * (1.0 - stop), Vector3d.Dot(world.GetVelocity(0), up), 9);
    }

    [Fact]
    public void Friction_never_reverses_a_slide_and_a_conveyor_drags_a_particle_to_its_speed()
    {
        // A plane moving along itself (a conveyor belt): geometry unchanged, its velocity enters the friction.
        var world = Ground(0.4, Vector3d.Zero, Vector3d.Zero);
        var belt = (PlaneObstacle)world.Constraints.OfType<ContactSet>().Single().Obstacles[0];
        belt.Velocity = new Vector3d(1.5, 0, 0);
        var rk4 = new RungeKutta4();
        for (var step = 1; step <= 100; step++)
        {
            world.Step(rk4, 0.01);
            var expected = Math.Min(1.5, 0.4 * G * step * 0.01);
            Assert.Equal(expected, world.GetVelocity(0).X, 12);
        }
    }

    private static ParticleWorld Ground(double mu, Vector3d position, Vector3d velocity)
    {
        var world = new ParticleWorld();
        world.AddParticle(position, velocity, 1);
        world.AddForce(Gravity.Down(G));
        var contacts = new ContactSet();
        contacts.Add(PlaneObstacle.Ground(0, mu));
        world.AddConstraints(contacts);
        return world;
    }

    internal static void StepFor(ParticleWorld world, string integrator, double dt, double duration)
    {
        var stepper = IntegratorCatalog.Create(integrator);
        var steps = (int)Math.Round(duration / dt);
        for (var s = 0; s < steps; s++)
        {
            world.Step(stepper, dt);
        }
    }
}
