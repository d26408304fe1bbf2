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
/// Reaction impulses for two-way coupling: a host that moves a collider as a free body by what the contact set reports
/// conserves the momentum of particles and body together; the angular impulse of a known impact is exact.
/// </summary>
[Collection(AllocationMeasurements.Name)]
public class ReactionTests(ITestOutputHelper output)
{
    [Theory]
    [InlineData("rk4", "sphere")]
    [InlineData("rk4", "mesh")]
    [InlineData("semi-implicit-euler", "sphere")]
    [InlineData("implicit-euler", "mesh")]
    [InlineData("xpbd", "sphere")]
    [InlineData("xpbd", "mesh")]
    public void A_host_moving_a_collider_as_a_free_body_by_its_reactions_conserves_momentum(string integrator, string shape)
    {
        // No gravity: particles of 0.2 to 0.5 kg thrown at a body of 3 kg, bouncing with restitution 0.6 and friction
        // 0.3, off centre so that friction acts. After each step the host adds the reported impulse to the body's
        // momentum and gives the body the velocity P / M for the next.
        const double bodyMass = 3.0;
        Obstacle body;
        if (shape == "sphere")
        {
            body = new SphereObstacle(Vector3d.Zero, 0.5, restitution: 0.6, friction: 0.3);
        }
        else
        {
            StandardMeshes.Icosphere(0.5, 2, out var vertices, out var triangles);
            body = new MeshObstacle(vertices, triangles, restitution: 0.6, friction: 0.3);
        }

        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(-2, 0.2, 0), new Vector3d(4, 0, 0), 0.5);
        world.AddParticle(new Vector3d(0.1, 2, 0.3), new Vector3d(0, -3, 0), 0.2);
        world.AddParticle(new Vector3d(1.5, -0.1, -1.5), new Vector3d(-2, 0.5, 2), 0.3);
        for (var i = 0; i < world.Count; i++)
        {
            world.SetRadius(i, 0.05);
        }

        var contacts = new ContactSet();
        contacts.Add(body);
        world.AddConstraints(contacts);
        var stepper = IntegratorCatalog.Create(integrator);
        var momentum = Vector3d.Zero;
        var start = Total(world, momentum);
        var impacts = 0;
        var worst = 0.0;
        for (var step = 1; step <= 1500; step++)
        {
            world.Step(stepper, 1e-3);
            impacts += contacts.ImpactCount;
            momentum += contacts.ReactionOf(body).Impulse;
            body.Rebase(world.Time);
            body.Velocity = momentum / bodyMass;
            worst = Math.Max(worst, (Total(world, momentum) - start).Length / start.Length);
        }

        output.WriteLine($"{integrator}, {shape}: worst drift of the total momentum {worst:E2} relative; body at {momentum / bodyMass} m/s");
        // Under xpbd a velocity is (x - x_prev) / h, whose rounding is that of the positions over h (1e-16 / 1e-4).
        Assert.True(integrator == "xpbd" || impacts >= 3, $"only {impacts} impacts");
        Assert.True(momentum.Length > 0.5, $"the body hardly moved: {momentum}");
        Assert.True(worst < (integrator == "xpbd" ? 1e-11 : 1e-14), $"the total momentum drifted by {worst:E2} relative");
    }

    [Fact]
    public void The_angular_impulse_of_one_impact_is_the_contact_point_cross_the_impulse()
    {
        // The contract's bouncing ball with friction: the first impact, at x = vx0 t1 on the ground, gives the ground
        // -m ((1 + e) u, up) and m mu (1 + e) u along x; about a point P the angular impulse is (c - P) x J.
        var scenario = new BouncingBallScenario { Friction = 0.3, Vx0 = 8.0 };
        var world = scenario.Build();
        var contacts = world.Constraints.OfType<ContactSet>().Single();
        var ground = contacts.Obstacles[0];
        var about = new Vector3d(-0.7, 0.4, 0.25);
        ground.ReactionPoint = about;
        var rk4 = new RungeKutta4();
        var step = (int)Math.Floor(scenario.FirstImpactTime / 0.001);
        for (var k = 0; k <= step; k++)
        {
            world.Step(rk4, 0.001);
        }

        var u = scenario.FirstImpactSpeed;
        var e = scenario.Restitution;
        var m = scenario.Mass;
        var impulse = new Vector3d(m * scenario.Friction * (1 + e) * u, -m * (1 + e) * u, 0);
        var contact = new Vector3d(scenario.Vx0 * scenario.FirstImpactTime, 0, 0);
        var reaction = contacts.ReactionOf(ground);
        var angular = Vector3d.Cross(contact - about, impulse);
        Assert.True((reaction.Impulse - impulse).Length < 1e-12 * impulse.Length, $"impulse {reaction.Impulse} vs {impulse}");
        Assert.True((reaction.AngularImpulse - angular).Length < 1e-12 * angular.Length, $"angular {reaction.AngularImpulse} vs {angular}");
    }

    [Fact]
    public void A_failed_step_shows_the_last_committed_reactions_and_reading_them_allocates_nothing()
    {
        var scenario = new BouncingBallScenario();
        var world = scenario.Build();
        var faulty = new FaultyForce();
        world.AddForce(faulty);
        var contacts = world.Constraints.OfType<ContactSet>().Single();
        var ground = contacts.Obstacles[0];
        var rk4 = new RungeKutta4();
        while (contacts.ReactionOf(ground).Impulse == Vector3d.Zero)
        {
            world.Step(rk4, 0.001);
        }

        var before = contacts.ReactionOf(ground);
        faulty.Arm(Fault.NaN);
        Assert.ThrowsAny<Exception>(() => world.Step(rk4, 0.001));
        Assert.Equal(before.Impulse, contacts.ReactionOf(ground).Impulse);
        Assert.Equal(before.AngularImpulse, contacts.ReactionOf(ground).AngularImpulse);
        Assert.Equal(0, ThreadAllocations.Measure(() => _ = contacts.ReactionOf(ground)));
        Assert.Throws<ArgumentException>(() => contacts.ReactionOf(new SphereObstacle(Vector3d.Zero, 1)));
    }

    private static Vector3d Total(ParticleWorld world, Vector3d body)
    {
        var total = body;
        for (var i = 0; i < world.Count; i++)
        {
            total += world.GetMass(i) * world.GetVelocity(i);
        }

        return total;
    }
}
