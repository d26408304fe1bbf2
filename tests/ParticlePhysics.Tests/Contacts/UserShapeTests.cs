using System;
using ParticlePhysics.Contacts;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Tests.Contacts;

/// <summary>
/// The extension point: a shape written outside the library (this assembly), a torus, which is not convex, joins a
/// contact set through <see cref="Obstacle"/>'s public members alone and gets impacts at their time, resting contact,
/// no tunnelling, casts and the broad phase like the library's own shapes.
/// </summary>
public class UserShapeTests
{
    [Fact]
    public void A_ball_dropped_on_the_top_of_the_tube_bounces_as_on_a_plane_at_its_height()
    {
        // Straight above the tube's top circle the normal is exactly +y, so the apexes are a plane's at y = a:
        // a + r + e^(2n) (h - a - r).
        var torus = new Torus(Vector3d.Zero, 1.0, 0.2, restitution: 0.8);
        var (world, _) = Drop(torus, new Vector3d(1.0, 1.5, 0), 0.05);
        var apexes = Apexes(world, new RungeKutta4(), 0.01, 4.0);
        for (var n = 1; n <= 4; n++)
        {
            var exact = 0.25 + (Math.Pow(0.8, 2 * n) * (1.5 - 0.25));
            Assert.True(Math.Abs(apexes[n - 1] - exact) < 1e-9 * exact, $"apex {n}: {apexes[n - 1]:R} against {exact:R}");
        }
    }

    [Theory]
    [InlineData("rk4")]
    [InlineData("xpbd")]
    public void A_ball_comes_to_rest_on_the_tube_and_one_through_the_hole_falls_freely(string integrator)
    {
        var torus = new Torus(Vector3d.Zero, 1.0, 0.2);
        var (world, _) = Drop(torus, new Vector3d(1.0, 0.6, 0), 0.05);
        world.AddParticle(new Vector3d(0, 0.6, 0), 1.0);
        world.SetRadius(1, 0.05);
        var free = new ParticleWorld();
        free.AddParticle(new Vector3d(0, 0.6, 0), 1.0);
        free.AddForce(new Gravity());
        var method = IntegratorCatalog.Create(integrator);
        var alone = IntegratorCatalog.Create(integrator);
        for (var step = 0; step < 120; step++)
        {
            world.Step(method, 1.0 / 60.0);
            free.Step(alone, 1.0 / 60.0);
        }

        Assert.True(Math.Abs(world.GetPosition(0).Y - 0.25) < 1e-6, $"rests at {world.GetPosition(0).Y:R}, not on the tube at 0.25");
        Assert.Equal(free.GetPosition(0), world.GetPosition(1)); // the hole is free: it falls as if alone
    }

    [Theory]
    [InlineData("rk4")]
    [InlineData("semi-implicit-euler")]
    [InlineData("xpbd")]
    public void A_particle_at_1000_m_per_s_meets_the_tube_2_cm_thick_instead_of_passing_it(string integrator)
    {
        var torus = new Torus(Vector3d.Zero, 1.0, 0.01, restitution: 0.5);
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(5, 0, 0), new Vector3d(-1000, 0, 0), 1.0);
        world.SetRadius(0, 0.001);
        var contacts = new ContactSet();
        contacts.Add(torus);
        world.AddConstraints(contacts);
        world.Step(IntegratorCatalog.Create(integrator), 1.0 / 60.0);
        Assert.True(world.GetPosition(0).X >= 1.011 - 1e-9, $"at x = {world.GetPosition(0).X:R}: through the tube");
        Assert.True(world.GetVelocity(0).X > 0, "it bounced back");
    }

    [Fact]
    public void The_default_cast_marches_to_the_surface()
    {
        var torus = new Torus(new Vector3d(0, 1, 0), 1.0, 0.2);
        Assert.True(torus.Cast(new Vector3d(1.0, 5, 0), new Vector3d(0, -1, 0), 0.0, 10, out var distance, out var normal, out var feature));
        Assert.True(Math.Abs(distance - 3.8) < 1e-11, $"{distance:R}");
        Assert.True((normal - new Vector3d(0, 1, 0)).Length < 1e-9);
        Assert.Equal(-1, feature);

        // Oblique, onto the outside of the tube: the hit is on the surface, the ray's first touch.
        var direction = new Vector3d(-1, -1, 0) / Math.Sqrt(2);
        Assert.True(torus.Cast(new Vector3d(3, 3, 0), direction, 0.1, 10, out distance, out _, out _));
        var at = new Vector3d(3, 3, 0) + (distance * direction);
        Assert.True(Math.Abs(torus.Distance(at.X, at.Y, at.Z, out _, out _, out _) - 0.1) < 1e-11);
        Assert.False(torus.Cast(new Vector3d(0, 5, 0), new Vector3d(0, -1, 0), 0.0, 10, out _, out _, out _)); // the hole
    }

    private static (ParticleWorld World, ContactSet Contacts) Drop(Obstacle obstacle, Vector3d from, double radius)
    {
        var world = new ParticleWorld();
        world.AddParticle(from, 1.0);
        world.SetRadius(0, radius);
        world.AddForce(new Gravity());
        var contacts = new ContactSet();
        contacts.Add(obstacle);
        world.AddConstraints(contacts);
        return (world, contacts);
    }

    private static System.Collections.Generic.List<double> Apexes(ParticleWorld world, IIntegrator integrator, double dt, double duration)
    {
        var apexes = new System.Collections.Generic.List<double>();
        var steps = (int)Math.Round(duration / dt);
        for (var step = 0; step < steps; step++)
        {
            var before = world.GetVelocity(0).Y;
            var y0 = world.GetPosition(0).Y;
            world.Step(integrator, dt);
            var after = world.GetVelocity(0).Y;
            if (before > 0 && after <= 0)
            {
                // The apex of the parabola through this step's start: y0 + v0^2 / (2 g).
                apexes.Add(y0 + (before * before / (2 * Gravity.StandardAcceleration)));
            }
        }

        return apexes;
    }

    /// <summary>
    /// A ring of radius R around the y axis through <see cref="Centre"/>, with a tube of radius a. With rho the distance
    /// from the axis, phi(p) = sqrt((rho - R)^2 + y^2) - a, the exact signed distance (1-Lipschitz, not convex); its
    /// gradient is (rho - R, y) / |(rho - R, y)| in the plane of the axis and p, turned back around the axis.
    /// </summary>
    private sealed class Torus : Obstacle
    {
        private readonly double _ring;
        private readonly double _tube;

        public Torus(Vector3d centre, double ring, double tube, double restitution = 0, double friction = 0)
            : base(restitution, friction)
        {
            Centre = centre;
            _ring = ring;
            _tube = tube;
        }

        public Vector3d Centre { get; private set; }

        public override void Translate(Vector3d offset) => Centre += offset;

        public override bool TryGetBounds(out Vector3d min, out Vector3d max)
        {
            var reach = new Vector3d(_ring + _tube, _tube, _ring + _tube);
            min = Centre - reach;
            max = Centre + reach;
            return true;
        }

        public override double Distance(double x, double y, double z, out double nx, out double ny, out double nz)
        {
            x -= Centre.X;
            y -= Centre.Y;
            z -= Centre.Z;
            var rho = Math.Sqrt((x * x) + (z * z));
            var radial = rho - _ring;
            var length = Math.Sqrt((radial * radial) + (y * y));
            var (ux, uz) = rho > 0 ? (x / rho, z / rho) : (1.0, 0.0);
            if (length > 0)
            {
                nx = radial / length * ux;
                ny = y / length;
                nz = radial / length * uz;
            }
            else
            {
                (nx, ny, nz) = (0, 1, 0);
            }

            return length - _tube;
        }

        protected override ObstacleShape Describe(Vector3d offset) => new(
            ObstacleKind.Custom, Centre + offset, new Vector3d(1, 0, 0), new Vector3d(0, 1, 0), new Vector3d(0, 0, 1),
            new Vector3d(_ring + _tube, _tube, _ring + _tube), 0.0);
    }
}
