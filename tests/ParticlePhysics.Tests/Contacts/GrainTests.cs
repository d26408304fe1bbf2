using System;
using ParticlePhysics.Contacts;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Tests.Contacts;

/// <summary>Grains are solid spheres that spin: against the exact rolling of a sphere, and all or nothing across a failed step.</summary>
public class GrainTests
{
    private const double G = 9.81;
    private const double R = 0.05;
    private readonly Xunit.Abstractions.ITestOutputHelper _output;

    public GrainTests(Xunit.Abstractions.ITestOutputHelper output)
    {
        _output = output;
    }

    [Fact]
    public void A_grain_sliding_onto_the_ground_ends_rolling_at_five_sevenths_of_its_speed()
    {
        // Angular momentum about the contact point is kept: m v0 r = m v r + (2/5) m r^2 (v / r), so v = 5/7 v0, reached
        // after t = 2 v0 / (7 mu g) = 0.194 s at mu = 0.3.
        var (world, contacts) = Grain(new Vector3d(0, R, 0), new Vector3d(2, 0, 0), PlaneObstacle.Ground(friction: 0.3));
        contacts.SetGranular(0, 1, 0.3, 0.0);
        Run(world, 1.0);
        var v = world.GetVelocity(0).X;
        var spin = contacts.GetSpin(0);
        _output.WriteLine($"after 1 s: v = {v:F6} m/s against 5/7 v0 = {10.0 / 7:F6}, spin {spin.Z:F4} rad/s against -v / r = {-v / R:F4}");
        Assert.True(Math.Abs(v - (10.0 / 7)) < 0.005 * 10 / 7, $"v = {v}");
        Assert.True(Math.Abs(spin.Z + (v / R)) < 1e-6 * v / R, $"spin {spin} at v = {v}: it slides");
        Assert.True(Math.Abs(spin.X) + Math.Abs(spin.Y) < 1e-12);
    }

    [Fact]
    public void A_grain_rolls_down_a_slope_at_five_sevenths_of_g_sin_theta_where_a_plain_particle_sticks()
    {
        // At 20 degrees with mu = 0.5 > (2/7) tan(theta), it rolls without slipping: s = (5/7) g sin(theta) t^2 / 2.
        const double theta = 20 * Math.PI / 180;
        var normal = new Vector3d(-Math.Sin(theta), Math.Cos(theta), 0);
        var along = new Vector3d(Math.Cos(theta), Math.Sin(theta), 0); // uphill
        foreach (var grain in new[] { true, false })
        {
            var (world, contacts) = Grain(R * normal, Vector3d.Zero, new PlaneObstacle(Vector3d.Zero, normal, 0, 0.5));
            if (grain)
            {
                contacts.SetGranular(0, 1, 0.5, 0.0);
            }

            Run(world, 1.0);
            var travelled = -Vector3d.Dot(world.GetPosition(0) - (R * normal), along);
            var expected = 0.5 * (5.0 / 7) * G * Math.Sin(theta);
            _output.WriteLine($"{(grain ? "grain" : "plain particle")}: {travelled:F6} m down the slope in 1 s; rolling gives {expected:F6} m");
            if (grain)
            {
                Assert.True(Math.Abs(travelled - expected) < 0.01 * expected, $"{travelled} m against {expected} m");
            }
            else
            {
                Assert.True(Math.Abs(travelled) < 1e-9, $"the plain particle moved {travelled} m");
            }
        }
    }

    [Fact]
    public void A_rolling_grain_stops_after_v_squared_over_two_five_sevenths_mu_r_g()
    {
        // A resisting torque mu_r r m g on a sphere that rolls: (m + I / r^2) dv/dt = -mu_r m g, so a = (5/7) mu_r g.
        const double muR = 0.1;
        var (world, contacts) = Grain(new Vector3d(0, R, 0), new Vector3d(1, 0, 0), PlaneObstacle.Ground(friction: 0.5));
        contacts.SetGranular(0, 1, 0.5, muR);
        contacts.SetSpin(0, new Vector3d(0, 0, -1 / R));
        Run(world, 2.0);
        var stop = world.GetPosition(0).X;
        var expected = 1 / (2 * (5.0 / 7) * muR * G);
        _output.WriteLine($"stopped after {stop:F5} m against v^2 / (2 (5/7) mu_r g) = {expected:F5} m; spin left {contacts.GetSpin(0).Length:E2} rad/s");
        Assert.True(Math.Abs(stop - expected) < 0.01 * expected, $"{stop} m against {expected} m");
        Assert.True(world.GetVelocity(0).Length < 1e-9 && contacts.GetSpin(0).Length < 1e-6);
    }

    [Fact]
    public void A_failed_step_leaves_the_spins_as_they_were_and_bad_grains_are_refused()
    {
        var (world, contacts) = Grain(new Vector3d(0, R, 0), new Vector3d(2, 0, 0), PlaneObstacle.Ground(friction: 0.3));
        contacts.SetGranular(0, 1, 0.3, 0.1);
        var (fresh, freshContacts) = Grain(new Vector3d(0, R, 0), new Vector3d(2, 0, 0), PlaneObstacle.Ground(friction: 0.3));
        freshContacts.SetGranular(0, 1, 0.3, 0.1);
        var xpbd = new Xpbd(10);
        for (var s = 0; s < 3; s++)
        {
            world.Step(xpbd, 1.0 / 60);
            fresh.Step(xpbd, 1.0 / 60);
        }

        var spin = contacts.GetSpin(0);
        Assert.NotEqual(Vector3d.Zero, spin);
        world.DivergenceLimit = 1e-3;
        Assert.Throws<SimulationDivergedException>(() => world.Step(xpbd, 1.0 / 60));
        Assert.Equal(spin, contacts.GetSpin(0));
        world.DivergenceLimit = double.MaxValue;
        world.Step(xpbd, 1.0 / 60);
        fresh.Step(xpbd, 1.0 / 60);
        Assert.Equal(freshContacts.GetSpin(0), contacts.GetSpin(0));
        Assert.Equal(fresh.Positions.ToArray(), world.Positions.ToArray());

        Assert.Contains("-1", Assert.Throws<ArgumentOutOfRangeException>(() => contacts.SetGranular(0, 1, -1, 0)).Message);
        Assert.Contains("NaN", Assert.Throws<ArgumentOutOfRangeException>(() => contacts.SetGranular(0, 1, 0.5, double.NaN)).Message);
        Assert.Contains("not a grain", Assert.Throws<ArgumentException>(() => contacts.SetSpin(5, Vector3d.Zero)).Message);
        Assert.False(contacts.IsGrain(5));
        Assert.Equal(Vector3d.Zero, contacts.GetSpin(5));
    }

    [Theory]
    [InlineData(20.0, 0.5)]
    [InlineData(30.0, 0.2)]
    public void A_grain_on_a_slope_stays_put_while_tan_theta_is_within_mu_r_and_rolls_at_five_sevenths_of_g_sin_less_mu_r_cos_past_it(double degrees, double muR)
    {
        // Held, friction m g sin(theta) <= mu N and the torque it makes, r m g sin(theta), within mu_r r N. Past that, the
        // rolling resistance is the torque mu_r r N: (7/5) m a = m g (sin(theta) - mu_r cos(theta)).
        var theta = degrees * Math.PI / 180;
        var normal = new Vector3d(-Math.Sin(theta), Math.Cos(theta), 0);
        var (world, contacts) = Grain(R * normal, Vector3d.Zero, new PlaneObstacle(Vector3d.Zero, normal, 0, 1.0));
        contacts.SetGranular(0, 1, 1.0, muR);
        Run(world, 1.0);
        var travelled = (world.GetPosition(0) - (R * normal)).Length;
        var rolls = Math.Tan(theta) > muR;
        var expected = rolls ? 0.5 * (5.0 / 7) * G * (Math.Sin(theta) - (muR * Math.Cos(theta))) : 0.0;
        _output.WriteLine($"{degrees} degrees, mu_r = {muR}: {travelled:E6} m in 1 s against {expected:E6} m");
        if (rolls)
        {
            Assert.True(Math.Abs(travelled - expected) < 0.01 * expected, $"{travelled} m against {expected} m");
        }
        else
        {
            Assert.True(travelled < 1e-12 && world.GetVelocity(0).Length < 1e-12 && contacts.GetSpin(0).Length < 1e-12, $"it crept {travelled} m");
        }
    }

    [Fact]
    public void A_pyramid_of_grains_that_cannot_roll_stands_as_one_of_plain_particles_does()
    {
        // Eight layers of square packing, 204 spheres of radius 1 cm, friction 1 between them and on the ground: plain
        // particles stand, and so do grains whose rolling friction never lets them roll.
        foreach (var grains in new[] { false, true })
        {
            var world = new ParticleWorld();
            world.AddForce(Gravity.Down(G));
            var contacts = new ContactSet { ParticleCollisions = true, ParticleFriction = 1.0 };
            contacts.Add(PlaneObstacle.Ground(friction: 1.0));
            world.AddConstraints(contacts);
            const double r = 0.01;
            for (var layer = 0; layer < 8; layer++)
            {
                var m = 8 - layer;
                for (var i = 0; i < m * m; i++)
                {
                    var p = new Vector3d(((i % m) - ((m - 1) / 2.0)) * 2 * r, r + (layer * Math.Sqrt(2) * r), ((i / m) - ((m - 1) / 2.0)) * 2 * r);
                    world.SetRadius(world.AddParticle(p, 1e-3), r);
                }
            }

            if (grains)
            {
                contacts.SetGranular(0, world.Count, 1.0, 100.0);
            }

            var start = new Vector3d[world.Count];
            for (var i = 0; i < world.Count; i++)
            {
                start[i] = world.GetPosition(i);
            }

            Run(world, 4.0);
            var moved = 0.0;
            for (var i = 0; i < world.Count; i++)
            {
                moved = Math.Max(moved, (world.GetPosition(i) - start[i]).Length);
            }

            _output.WriteLine($"{(grains ? "grains" : "plain particles")}: after 4 s the farthest of {world.Count} moved {moved:E2} m");
            Assert.True(moved < 1e-3, $"the pyramid of {(grains ? "grains" : "plain particles")} slumped: a particle moved {moved} m");
        }
    }

    private static (ParticleWorld World, ContactSet Contacts) Grain(Vector3d position, Vector3d velocity, Obstacle ground)
    {
        var world = new ParticleWorld();
        world.AddParticle(position, velocity, 1.0);
        world.SetRadius(0, R);
        world.AddForce(Gravity.Down(G));
        var contacts = new ContactSet();
        contacts.Add(ground);
        world.AddConstraints(contacts);
        return (world, contacts);
    }

    private static void Run(ParticleWorld world, double duration)
    {
        var xpbd = new Xpbd(10);
        for (var s = 0; s < (int)Math.Round(duration * 60); s++)
        {
            world.Step(xpbd, 1.0 / 60);
        }
    }
}
