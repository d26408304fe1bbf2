using System;
using System.Linq;
using ParticlePhysics.Contacts;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Tests.Contacts;

/// <summary>
/// The contact set inside position-based substeps (Project, then SolveVelocities), driven by a test-local substep loop
/// in the shape of Macklin et al.'s "Small Steps": v += h g; x_prev = x; x += h v; Project; v = (x - x_prev) / h;
/// SolveVelocities.
/// </summary>
public class SubstepContactTests
{
    [Fact]
    public void A_ball_bounces_to_the_apex_heights_to_first_order_in_the_substep()
    {
        var scenario = new BouncingBallScenario();
        var errors = new double[2];
        for (var level = 0; level < 2; level++)
        {
            var loop = new SubstepLoop(scenario.Build(), 9.81);
            var h = 0.001 / (10 << level);
            var apexes = loop.Apexes(h, 3.0);
            for (var n = 1; n <= 5; n++)
            {
                errors[level] = Math.Max(errors[level], Math.Abs(apexes[n - 1] - scenario.ApexHeight(n)) / scenario.ApexHeight(n));
            }
        }

        // An impact is resolved at the end of its substep, not at its time: the rebound loses up to u h of height, an
        // error of first order whose size depends on where the impact falls, so it shrinks with h, if not by exactly half.
        Assert.True(errors[0] < 2e-3, $"apex error {errors[0]}");
        Assert.True(errors[1] < errors[0], $"errors {errors[0]} then {errors[1]}: not converging");
    }

    [Fact]
    public void A_resting_particle_stays_exactly_on_the_ground_and_a_slide_stops_near_v0_squared_over_2_mu_g()
    {
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(0, 0.1, 0), new Vector3d(2, 0, 0), 1);
        world.SetRadius(0, 0.1);
        var contacts = new ContactSet();
        contacts.Add(PlaneObstacle.Ground(0.5, 0.4));
        world.AddConstraints(contacts);
        var loop = new SubstepLoop(world, 9.81);
        loop.Run(1.0 / 600.0, 1.0);
        Assert.Equal(0.1, world.GetPosition(0).Y, 12);
        Assert.True(Math.Abs(world.GetVelocity(0).Y) < 1e-12);
        Assert.Equal(0.0, world.GetVelocity(0).X, 12);
        var exact = 4.0 / (2 * 0.4 * 9.81);
        Assert.True(Math.Abs(world.GetPosition(0).X - exact) < 0.01 * exact, $"{world.GetPosition(0).X} vs {exact}");
    }

    [Fact]
    public void Particles_collide_conserving_momentum_and_nothing_crosses_a_thin_wall()
    {
        var scenario = new CollisionScenario { Mass2 = 3, Restitution = 0.5 };
        var world = scenario.Build();
        var before = world.TotalMomentum();
        new SubstepLoop(world, 0).Run(0.0001, 2.0);
        Assert.True((world.TotalMomentum() - before).Length < 1e-12);
        Assert.Equal(scenario.FinalVelocity1, world.GetVelocity(0).X, 3);
        Assert.Equal(scenario.FinalVelocity2, world.GetVelocity(1).X, 3);

        var fast = new ParticleWorld();
        fast.AddParticle(Vector3d.Zero, new Vector3d(1000, 0, 0), 1);
        var contacts = new ContactSet();
        contacts.Add(new BoxObstacle(new Vector3d(10, 0, 0), new Vector3d(0.001, 5, 5)));
        fast.AddConstraints(contacts);
        var wall = new SubstepLoop(fast, 0);
        for (var step = 0; step < 100; step++)
        {
            wall.Run(1.0 / 600.0, 1.0 / 600.0);
            Assert.True(fast.GetPosition(0).X <= 10 - 0.001 + 1e-9, $"crossed to {fast.GetPosition(0)}");
        }
    }

    /// <summary>The shape of the xpbd integrator's substep, with gravity as the only force.</summary>
    private sealed class SubstepLoop
    {
        private readonly ParticleWorld _world;
        private readonly double _gravity;

        public SubstepLoop(ParticleWorld world, double gravity)
        {
            _world = world;
            _gravity = gravity;
        }

        public void Run(double h, double duration)
        {
            var steps = (int)Math.Round(duration / h);
            for (var k = 0; k < steps; k++)
            {
                Substep(h);
            }
        }

        public double[] Apexes(double h, double duration)
        {
            var apexes = new System.Collections.Generic.List<double>();
            var steps = (int)Math.Round(duration / h);
            for (var k = 0; k < steps; k++)
            {
                var y = _world.GetPosition(0).Y;
                var vy = _world.GetVelocity(0).Y;
                Substep(h);
                if (vy > 0 && _world.GetVelocity(0).Y <= 0)
                {
                    apexes.Add(Math.Max(y, _world.GetPosition(0).Y));
                }
            }

            return apexes.ToArray();
        }

        private void Substep(double h)
        {
            var n = _world.Count;
            var start = _world.State.ToArray();
            var x = new double[3 * n];
            var v = new double[3 * n];
            for (var i = 0; i < n; i++)
            {
                for (var c = 0; c < 3; c++)
                {
                    var free = _world.InverseMasses[i] != 0;
                    v[(3 * i) + c] = start[(3 * n) + (3 * i) + c] - (c == 1 && free ? h * _gravity : 0.0);
                    x[(3 * i) + c] = start[(3 * i) + c] + (h * v[(3 * i) + c]);
                }
            }

            var set = _world.Constraints.OfType<ContactSet>().Single();
            var context = new ConstraintContext(
                _world.Time, h, start.AsSpan(0, 3 * n), start.AsSpan(3 * n), x, v, _world.Masses, _world.InverseMasses, _world.Radii);
            set.Project(in context);
            for (var k = 0; k < 3 * n; k++)
            {
                v[k] = (x[k] - start[k]) / h;
            }

            set.SolveVelocities(in context);
            var next = new double[6 * n];
            x.CopyTo(next, 0);
            v.CopyTo(next, 3 * n);
            _world.SetState(next);
            _world.Time += h;
        }
    }
}

/// <summary>The contact set under the world's own xpbd integrator (its substeps call Project and SolveVelocities).</summary>
public class XpbdContactTests
{
    [Fact]
    public void Under_xpbd_the_ball_bounces_near_the_exact_apexes_and_rests_on_its_radius()
    {
        var scenario = new BouncingBallScenario { Radius = 0.1 };
        var world = scenario.Build();
        var xpbd = new ParticlePhysics.Integrators.Xpbd(10);
        var apexes = new System.Collections.Generic.List<double>();
        for (var step = 0; step < 5000; step++)
        {
            var y = world.GetPosition(0).Y;
            var vy = world.GetVelocity(0).Y;
            world.Step(xpbd, 0.001);
            if (vy > 0 && world.GetVelocity(0).Y <= 0)
            {
                apexes.Add(Math.Max(y, world.GetPosition(0).Y));
            }
        }

        for (var n = 1; n <= 5; n++)
        {
            Assert.True(Math.Abs(apexes[n - 1] - scenario.ApexHeight(n)) < 2e-3 * scenario.ApexHeight(n), $"apex {n}: {apexes[n - 1]} vs {scenario.ApexHeight(n)}");
        }

        Assert.Equal(0.1, world.GetPosition(0).Y, 12);
        Assert.True(Math.Abs(world.GetVelocity(0).Y) < 1e-3);
    }

    public static TheoryData<string, string, double> MovingObstacles()
    {
        var data = new TheoryData<string, string, double>();
        foreach (var integrator in ParticlePhysics.Integrators.IntegratorCatalog.Names)
        {
            data.Add(integrator, "box", 20);
            data.Add(integrator, "box", 1e4);
            data.Add(integrator, "sphere", 50);
        }

        return data;
    }

    [Theory]
    [MemberData(nameof(MovingObstacles))]
    public void A_moving_thin_obstacle_carries_a_resting_particle_along_instead_of_passing_through_it(string integrator, string shape, double speed)
    {
        // Issue 27, item 6: under xpbd a 2 mm box at 20 m/s (or 1e4 m/s), or a 5 cm sphere at 50 m/s, passed through a
        // particle at rest and left it at x = 0: the particle was held at the point where it touched, which stood still
        // while the obstacle moved on. With e = 0 the obstacle must carry it on its front face at its own speed.
        const double r = 0.01;
        var world = new ParticleWorld();
        world.AddParticle(Vector3d.Zero, 1);
        world.SetRadius(0, r);
        Obstacle obstacle = shape == "box"
            ? new BoxObstacle(new Vector3d(-1, 0, 0), new Vector3d(0.001, 1, 1))
            : new SphereObstacle(new Vector3d(-1, 0, 0), 0.05);
        obstacle.Velocity = new Vector3d(speed, 0, 0);
        var contacts = new ContactSet();
        contacts.Add(obstacle);
        world.AddConstraints(contacts);
        var stepper = ParticlePhysics.Integrators.IntegratorCatalog.Create(integrator);
        var front = shape == "box" ? 0.001 : 0.05;
        for (var step = 1; step <= 30; step++)
        {
            world.Step(stepper, 1.0 / 60.0);
            var face = obstacle.ShapeAt(world.Time).Center.X + front;
            if (face > -r)
            {
                Assert.True(world.GetPosition(0).X >= face + r - 1e-6, $"step {step}: the particle at {world.GetPosition(0)} is behind the face at {face}");
                Assert.True(Math.Abs(world.GetVelocity(0).X - speed) <= 1e-9 * speed, $"step {step}: moving at {world.GetVelocity(0)}");
            }
        }
    }

    [Fact]
    public void Under_xpbd_nothing_crosses_a_thin_wall_and_the_draped_cloth_stays_out_of_the_sphere()
    {
        var fast = new ParticleWorld();
        fast.AddParticle(Vector3d.Zero, new Vector3d(1000, 0, 0), 1);
        var contacts = new ContactSet();
        contacts.Add(new BoxObstacle(new Vector3d(10, 0, 0), new Vector3d(0.001, 5, 5)));
        fast.AddConstraints(contacts);
        var xpbd = new ParticlePhysics.Integrators.Xpbd();
        for (var step = 0; step < 60; step++)
        {
            fast.Step(xpbd, 1.0 / 60.0);
            Assert.True(fast.GetPosition(0).X <= 10 - 0.001 + 1e-9, $"crossed to {fast.GetPosition(0)}");
        }

        var drape = new DrapeScenario();
        var world = drape.Build();
        var sphere = world.Constraints.OfType<ContactSet>().Single().Obstacles[0];
        for (var step = 0; step < 60; step++)
        {
            world.Step(xpbd, 1.0 / 60.0);
            for (var i = 0; i < world.Count; i++)
            {
                Assert.True(sphere.SignedDistance(world.GetPosition(i), out _) - drape.Radius >= -1e-6, $"particle {i} inside at step {step}");
            }
        }
    }
}
