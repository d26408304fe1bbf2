using System;
using ParticlePhysics.Constraints;
using ParticlePhysics.Forces;
using ParticlePhysics.Parallel;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Implicit;

/// <summary>
/// <see cref="ILinearizableSystem.AccumulateForcesAndLinearize"/> (one pass over a spring network) against the three
/// calls it replaces, AccumulateForces, Linearize and AddDiagonalBlocks: the same forces, (df/dx) v, diagonal blocks and
/// Jacobian products, to the last bit, on one core and on a runner.
/// </summary>
public class FusedLinearizationTests
{
    public static TheoryData<string> Worlds() => new() { "mixed", "cloth", "cloth-on-runner" };

    [Theory]
    [MemberData(nameof(Worlds))]
    public void The_fused_call_gives_the_bits_of_the_three_separate_calls(string kind)
    {
        using var runner = kind == "cloth-on-runner" ? new WorkerThreadRunner(2) : null;
        var separate = Build(kind);
        var fused = Build(kind);
        separate.Runner = runner;
        fused.Runner = runner;
        ILinearizableSystem a = separate, b = fused;
        var n = separate.CoordinateCount;
        var x = separate.Positions.ToArray();
        var v = separate.Velocities.ToArray();
        const double h = 1.0 / 60;

        var forcesA = a.AccumulateForces(2.5, x, v).ToArray();
        var jvA = new double[n];
        var blocksA = new double[3 * n];
        a.Linearize(2.5, x, v, h * h, h, UserForceTreatment.FiniteDifference, jvA);
        a.AddDiagonalBlocks(blocksA);

        var jvB = new double[n];
        var blocksB = new double[3 * n];
        var forcesB = b.AccumulateForcesAndLinearize(2.5, x, v, h * h, h, UserForceTreatment.FiniteDifference, jvB, blocksB).ToArray();

        Assert.Equal(StateMetrics.BitHash(forcesA), StateMetrics.BitHash(forcesB));
        Assert.Equal(StateMetrics.BitHash(jvA), StateMetrics.BitHash(jvB));
        Assert.Equal(StateMetrics.BitHash(blocksA), StateMetrics.BitHash(blocksB));

        // The stored linearisation is the same too: products with a vector that is not smooth.
        var w = new double[n];
        for (var k = 0; k < n; k++)
        {
            w[k] = Math.Sin(1.7 * k) + (0.25 * (k % 7));
        }

        var productA = new double[n];
        var productB = new double[n];
        a.AddJacobianProduct(w, productA);
        b.AddJacobianProduct(w, productB);
        Assert.Equal(StateMetrics.BitHash(productA), StateMetrics.BitHash(productB));

        // And non-trivially so: every kind of term is there.
        Assert.Contains(forcesB, f => f != 0.0);
        Assert.Contains(jvB, y => y != 0.0);
        Assert.Contains(blocksB, d => d != 0.0);
    }

    [Fact]
    public void The_fused_call_checks_its_buffers()
    {
        ILinearizableSystem world = Build("mixed");
        var n = world.CoordinateCount;
        var x = new double[n];
        var v = new double[n];
        var error = Assert.Throws<ArgumentException>(() =>
            world.AccumulateForcesAndLinearize(0, x, v, 1, 1, UserForceTreatment.Explicit, new double[n], new double[(3 * n) - 1]));
        Assert.Contains("diagonalBlocks", error.Message, StringComparison.Ordinal);
        Assert.Throws<ArgumentException>(() =>
            world.AccumulateForcesAndLinearize(0, x, v, 1, 1, UserForceTreatment.Explicit, new double[n - 1], new double[3 * n]));
    }

    /// <summary>
    /// "mixed": a few particles with every force kind the world can linearise (springs between particles, one of zero
    /// length at the moment, anchored springs, zero-length springs, dampers, drag, gravity, a user force wrapped in
    /// finite differences) and a rod that acts through constraint forces; "cloth": the 40 x 40 course cloth (9 048
    /// springs, above the spring network's parallel threshold), disturbed so that nothing is symmetric.
    /// </summary>
    private static ParticleWorld Build(string kind)
    {
        if (kind != "mixed")
        {
            var cloth = new ClothScenario { Resolution = 1.0 / 39 }.Build();
            for (var i = 0; i < cloth.Count; i++)
            {
                var p = cloth.GetPosition(i);
                cloth.SetPosition(i, new Vector3d(p.X + (0.01 * Math.Sin(i)), p.Y + (0.02 * Math.Cos(3 * i)), p.Z + (0.01 * Math.Sin(7 * i))));
                if (!cloth.IsPinned(i))
                {
                    cloth.SetVelocity(i, new Vector3d(Math.Cos(i), 0.5 * Math.Sin(2 * i), 0.1 * i / cloth.Count));
                }
            }

            return cloth;
        }

        var world = new ParticleWorld();
        for (var i = 0; i < 6; i++)
        {
            world.AddParticle(new Vector3d(0.3 * i, Math.Sin(i), 0.1 * i * i), new Vector3d(Math.Cos(i), 0.2 * i, -0.3), 1.0 + (0.1 * i));
        }

        world.SetPosition(5, world.GetPosition(4)); // a spring of zero length: no direction
        world.Pin(0);
        var springs = new SpringNetwork(world);
        springs.Add(0, 1, 40, 0.25, 0.3);
        springs.Add(1, 2, 55, 0.5, 0.1);
        springs.Add(2, 3, 30, 2.0, 0.2); // compressed: the transverse term clamps
        springs.Add(4, 5, 20, 0.1, 0.4);
        springs.Add(3, 5, 25, 0.0, 0.0);
        springs.AddAnchored(3, new Vector3d(1, 2, 3), 15, 0.5, 0.2);
        springs.AddAnchored(1, new Vector3d(-1, 0, 0.5), 12, 0.0, 0.1);
        world.AddForce(springs);
        var zeroLength = new ZeroLengthSprings(world);
        zeroLength.Add(1, 4, 7);
        world.AddForce(zeroLength);
        var dampers = new Dampers(world);
        dampers.Add(2, 4, 0.6);
        world.AddForce(dampers);
        world.AddForce(new LinearDrag(0.05));
        world.AddForce(new Gravity(new Vector3d(0, -9.81, 0)));
        world.AddForce(new HarmonicDrive(0.7, 2.0));
        var rods = new RodNetwork(world);
        rods.AddRod(2, 3, 1.3);
        world.AddConstraints(rods);
        return world;
    }
}
