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

    public static TheoryData<string, double> EveryIntegratorAtFrameSteps()
    {
        var data = new TheoryData<string, double>();
        foreach (var name in IntegratorCatalog.Names)
        {
            data.Add(name, 1.0 / 60.0);
            data.Add(name, 0.0238);
        }

        return data;
    }

    [Theory]
    [MemberData(nameof(EveryIntegratorAtFrameSteps))]
    public void A_particle_at_rest_on_an_incline_facing_any_way_sticks_whatever_residue_its_velocity_has(string integrator, double dt)
    {
        // Found by the API fuzz's incline probe: on 6 degrees with mu = 1.57 tan(theta), the plane facing +z, RK4 at
        // 0.0238 s moved a particle 5 mm in 22 steps. After a step its velocity was a rounding residue of 1e-17 m/s in
        // some direction across the slope, friction was decided along that direction alone, and the slope's pull across
        // it went unopposed. Whatever the plane's heading, a particle at rest must stay at rest.
        foreach (var heading in new[] { 0.5 * Math.PI, 1.0, 3.14159, 5.288777992022244 })
        {
            foreach (var degrees in new[] { 6.0, 30.0 })
            {
                var theta = degrees * Math.PI / 180;
                var normal = new Vector3d(Math.Sin(theta) * Math.Cos(heading), Math.Cos(theta), Math.Sin(theta) * Math.Sin(heading));
                var start = new Vector3d(1.9, -0.2, 1.6);
                var world = new ParticleWorld();
                world.AddParticle(start, 1);
                world.AddForce(Gravity.Down(G));
                var contacts = new ContactSet();
                contacts.Add(new PlaneObstacle(start, normal, 0, 1.04 * Math.Tan(theta)));
                world.AddConstraints(contacts);
                StepFor(world, integrator, dt, 0.5);
                Assert.True((world.GetPosition(0) - start).Length < 1e-12, $"heading {heading}, {degrees} degrees: moved {(world.GetPosition(0) - start).Length:R} m");
                Assert.True(world.GetVelocity(0).Length < 1e-12, $"heading {heading}, {degrees} degrees: moving at {world.GetVelocity(0)}");
            }
        }
    }

    [Theory]
    [MemberData(nameof(IntegratorsAndSteps))]
    public void Under_every_force_based_integrator_a_slide_down_an_incline_follows_the_exact_motion(string integrator, double dt)
    {
        // Found by the API fuzz's incline probe: under explicit Euler a slide just begun went back up the slope, since
        // friction's -f tau^2 / 2 was added to a displacement that holds none of the applied force's a tau^2 / 2; and
        // just past the friction cone (mu = 0.999 tan(theta)), with the slope facing another way than -x, friction taken
        // along the start velocity's direction for a whole step swung a slow slide from side to side (0.0015 m in 5 s
        // where it slides 0.061 m; before that, along a rounding residue's direction, 0.45 m). From rest on 30 degrees:
        // s = g (sin - mu cos) t^2 / 2, never decreasing, straight down the slope.
        var theta = 30 * Math.PI / 180;
        foreach (var (heading, mu, duration) in new[] { (Math.PI, 0.5, 1.0), (1.0, 0.5, 1.0), (1.0, 0.999 * Math.Tan(theta), 5.0) })
        {
            var normal = new Vector3d(Math.Sin(theta) * Math.Cos(heading), Math.Cos(theta), Math.Sin(theta) * Math.Sin(heading));
            var slope = new Vector3d(0, -G, 0) + (G * normal.Y * normal);
            var down = slope / slope.Length;
            var world = new ParticleWorld();
            world.AddParticle(Vector3d.Zero, 1);
            world.AddForce(Gravity.Down(G));
            var contacts = new ContactSet();
            contacts.Add(new PlaneObstacle(Vector3d.Zero, normal, 0, mu));
            world.AddConstraints(contacts);
            var stepper = IntegratorCatalog.Create(integrator);
            var acceleration = G * (Math.Sin(theta) - (mu * Math.Cos(theta)));
            var steps = (int)Math.Round(duration / dt);
            var before = 0.0;
            for (var step = 1; step <= steps; step++)
            {
                world.Step(stepper, dt);
                var along = Vector3d.Dot(world.GetPosition(0), down);
                Assert.True(along >= before, $"heading {heading}, mu {mu}, step {step}: back up the slope from {before} to {along}");
                before = along;
            }

            var what = $"heading {heading}, mu {mu}";
            var exact = 0.5 * acceleration * duration * duration;
            Assert.True(Math.Abs(before - exact) < 1e-12, $"{what}: slid {before:R}, exactly {exact:R}");
            Assert.True((world.GetPosition(0) - (before * down)).Length < 1e-12, $"{what}: off the line of steepest descent by {(world.GetPosition(0) - (before * down)).Length}");
            Assert.True((world.GetVelocity(0) - (acceleration * duration * down)).Length < 1e-12, $"{what}: moving at {world.GetVelocity(0)}");
        }
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
