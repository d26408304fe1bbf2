using System;
using System.Linq;
using ParticlePhysics.Contacts;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Tests.Contacts;

/// <summary>
/// Piles of grains poured onto rough ground: their slope against the rolling friction, the measurement behind
/// docs/scenes.md's note that piles do not stand still yet (they keep flowing outward for seconds).
/// </summary>
public class GrainPileTests
{
    private const double R = 0.01;
    private readonly Xunit.Abstractions.ITestOutputHelper _output;

    public GrainPileTests(Xunit.Abstractions.ITestOutputHelper output)
    {
        _output = output;
    }

    [Fact]
    [Trait("Category", "Long")]
    public void A_poured_pile_is_steeper_the_more_its_grains_resist_rolling_and_spreads_flat_without_it()
    {
        // 2,000 grains of radius 1 cm and 1 g, eight a frame from a disc of radius 4 cm, 25 cm up, falling at 1 m/s,
        // onto ground of friction 1; friction 0.6 between grains; then 4 s to settle. The slope is atan(H / R95): the
        // pile's height over the radius that holds 95 % of its grains (a cone's tan(angle)). Plain particles (no spin:
        // infinite rolling resistance) are the limit.
        var rows = new[] { 0.0, 0.1, 0.3, double.PositiveInfinity }.Select(muR => (MuR: muR, Pile: Pour(2000, 0.6, muR))).ToArray();
        _output.WriteLine("mu_r | height (m) | R95 (m) | atan(H / R95) | farthest move in the last second (m) | mean outward, up (mm)");
        foreach (var (muR, pile) in rows)
        {
            _output.WriteLine($"{(double.IsInfinity(muR) ? "no spin" : muR.ToString("F1", System.Globalization.CultureInfo.InvariantCulture))} | {pile.Height:F3} | {pile.Radius95:F3} | {pile.Slope:F1} | {pile.Moved:E2} | {1e3 * pile.Outward:F2}, {1e3 * pile.Up:F2}");
        }

        // Without rolling resistance spheres roll apart on rough ground: the pile is a layer.
        Assert.True(rows[0].Pile.Height < 3 * R, $"without rolling friction the pile stands {rows[0].Pile.Height} m high");
        Assert.True(rows[1].Pile.Slope > rows[0].Pile.Slope && rows[2].Pile.Slope > rows[1].Pile.Slope, "the slope does not rise with the rolling friction");
        Assert.True(rows[3].Pile.Slope > rows[1].Pile.Slope, "plain particles make a flatter pile than grains that roll");
    }

    private static Pile Pour(int count, double mu, double muR)
    {
        var world = new ParticleWorld();
        world.AddForce(Gravity.Down(9.81));
        var contacts = new ContactSet { ParticleCollisions = true, ParticleFriction = mu };
        contacts.Add(PlaneObstacle.Ground(friction: 1.0));
        if (!double.IsInfinity(muR))
        {
            contacts.SetGranular(0, count, mu, muR);
        }

        world.AddConstraints(contacts);
        var xpbd = new Xpbd(10);
        var seed = 12345UL;
        double Next()
        {
            seed = (seed * 6364136223846793005UL) + 1442695040888963407UL;
            return (seed >> 11) * (1.0 / (1UL << 53));
        }

        while (world.Count < count)
        {
            for (var k = 0; k < 8 && world.Count < count; k++)
            {
                var angle = Next() * 2 * Math.PI;
                var d = 0.04 * Math.Sqrt(Next());
                world.SetRadius(world.AddParticle(new Vector3d(d * Math.Cos(angle), 0.25 + (0.025 * k), d * Math.Sin(angle)), new Vector3d(0, -1, 0), 1e-3), R);
            }

            world.Step(xpbd, 1.0 / 60);
        }

        var before = new Vector3d[count];
        for (var s = 0; s < 240; s++)
        {
            if (s == 180)
            {
                for (var i = 0; i < count; i++)
                {
                    before[i] = world.GetPosition(i);
                }
            }

            world.Step(xpbd, 1.0 / 60);
        }

        var radii = new double[count];
        double height = 0, moved = 0, outward = 0, up = 0;
        var moving = 0;
        for (var i = 0; i < count; i++)
        {
            var p = world.GetPosition(i);
            var q = before[i];
            radii[i] = Math.Sqrt((p.X * p.X) + (p.Z * p.Z));
            height = Math.Max(height, p.Y + R);
            moved = Math.Max(moved, (p - q).Length);
            if ((p - q).Length > 1e-3)
            {
                moving++;
                outward += radii[i] - Math.Sqrt((q.X * q.X) + (q.Z * q.Z));
                up += p.Y - q.Y;
            }
        }

        Array.Sort(radii);
        var radius95 = radii[(int)(0.95 * (count - 1))] + R;
        return new Pile(height, radius95, Math.Atan(height / radius95) * 180 / Math.PI, moved, moving > 0 ? outward / moving : 0, moving > 0 ? up / moving : 0);
    }

    private readonly record struct Pile(double Height, double Radius95, double Slope, double Moved, double Outward, double Up);
}
