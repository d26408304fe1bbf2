using System;
using System.Linq;
using ParticlePhysics.Contacts;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Contacts;

/// <summary>
/// Any number of obstacles, through a broad phase over their boxes: it changes which obstacles the stages test, never
/// what they do, so a world gives the same bits as when every stage tests every obstacle (the stages before the broad
/// phase), whether it scans the boxes (a few obstacles) or descends a tree (many), with obstacles moving or still.
/// </summary>
public class ObstacleBroadPhaseTests
{
    [Theory]
    [InlineData("rk4", 6, 300, 90)]
    [InlineData("rk4", 150, 300, 90)]
    [InlineData("semi-implicit-euler", 150, 300, 90)]
    [InlineData("xpbd", 150, 100, 30)]
    public void A_world_of_many_obstacles_gives_the_bits_of_testing_every_obstacle(string integrator, int obstacles, int particles, int steps)
    {
        var (world, contacts) = Build(obstacles, 7, particles);
        var (brute, bruteContacts) = Build(obstacles, 7, particles);
        bruteContacts.TestEveryObstacle = true;
        var a = IntegratorCatalog.Create(integrator);
        var b = IntegratorCatalog.Create(integrator);
        var impacts = 0;
        for (var step = 0; step < steps; step++)
        {
            world.Step(a, 1.0 / 60.0);
            brute.Step(b, 1.0 / 60.0);
            impacts += contacts.ImpactCount;
            Assert.Equal(bruteContacts.ImpactCount, contacts.ImpactCount);
        }

        Assert.True(impacts > 20, $"only {impacts} impacts: the test would test little");
        var x = world.State.ToArray();
        var y = brute.State.ToArray();
        for (var k = 0; k < x.Length; k++)
        {
            Assert.Equal(BitConverter.DoubleToInt64Bits(y[k]), BitConverter.DoubleToInt64Bits(x[k]));
        }
    }

    [Fact]
    public void A_step_among_a_thousand_obstacles_allocates_nothing_once_warm()
    {
        var (world, _) = Build(1000, 3);
        var rk4 = new RungeKutta4();
        for (var step = 0; step < 20; step++)
        {
            world.Step(rk4, 1.0 / 60.0);
        }

        Assert.Equal(0, ThreadAllocations.Measure(() => world.Step(rk4, 1.0 / 60.0)));
    }

    /// <summary>
    /// Particles (300 by default) of 4 cm falling at up to 5 m/s into a field of spheres, capsules and turned boxes over the ground,
    /// a third of them moving; the particles collide with each other too.
    /// </summary>
    internal static (ParticleWorld World, ContactSet Contacts) Build(int obstacles, uint seed, int particles = 300)
    {
        var state = seed;
        double Next() => ObstacleTests.Next(ref state);
        var world = new ParticleWorld();
        for (var i = 0; i < particles; i++)
        {
            var p = new Vector3d(4 * Next(), 1.5 + Next(), 4 * Next());
            world.AddParticle(p, new Vector3d(5 * Next(), 5 * Next(), 5 * Next()), 0.1);
            world.SetRadius(i, 0.04);
        }

        world.AddForce(new Gravity());
        var contacts = new ContactSet { ParticleCollisions = true, ParticleRestitution = 0.3, ParticleFriction = 0.2 };
        contacts.Add(PlaneObstacle.Ground(0.5, 0.4));
        for (var k = 1; k < obstacles; k++)
        {
            var centre = new Vector3d(4.5 * Next(), 0.6 + (0.5 * Next()), 4.5 * Next());
            var size = 0.1 + (0.1 * Math.Abs(Next()));
            Obstacle obstacle = (k % 3) switch
            {
                0 => new SphereObstacle(centre, size, 0.6, 0.3),
                1 => new CapsuleObstacle(centre, centre + new Vector3d(Next(), 0.2 * Next(), Next()), 0.5 * size, 0.2, 0.5),
                _ => TurnedBox(centre, size, Next(), Next()),
            };
            if (k % 3 == 1)
            {
                obstacle.Velocity = new Vector3d(Next(), 0.5 * Next(), Next());
            }

            contacts.Add(obstacle);
        }

        world.AddConstraints(contacts);
        return (world, contacts);
    }

    private static BoxObstacle TurnedBox(Vector3d centre, double size, double a, double b)
    {
        var box = new BoxObstacle(centre, new Vector3d(size, 0.5 * size, 1.5 * size), 0.1, 0.6);
        box.SetOrientation(new Vector3d(1, a, b), new Vector3d(b, 1, a));
        return box;
    }
}
