using System;
using ParticlePhysics.Constraints;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Constraints;

/// <summary>The hanging chain of rods settles into the discrete catenary.</summary>
public class HangingChainTests
{
    [Theory]
    [InlineData(3)]
    [InlineData(11)]
    [InlineData(21)]
    [InlineData(51)]
    public void Under_rk4_it_comes_to_rest_within_1e_4_of_the_discrete_catenary(int n)
    {
        var scenario = new HangingChainScenario { Particles = n };
        var world = scenario.Build();
        var rods = (RodNetwork)world.Constraints[0];
        Assert.True(rods.SolvesDirectly);
        var rk4 = new RungeKutta4();
        var worst = 0.0;
        for (var s = 0; s < 20000; s++)
        {
            world.Step(rk4, HangingChainScenario.DefaultTimeStep);
            worst = Math.Max(worst, rods.MaxRelativeViolation(world.Positions));
        }

        var rest = scenario.RestShape();
        var distance = rest.MaxDistance(world.Positions);
        Assert.True(distance < 1e-4, $"N = {n}: {distance:E3} m from the catenary");
        Assert.True(worst < 1e-9, $"N = {n}: a rod drifted {worst:E3} of its length");

        // At rest every rod carries the horizontal tension H: T_j cos(phi_j) = H.
        _ = world.AccumulateForces(world.Time, world.Positions, world.Velocities);
        var x = world.Positions;
        for (var j = 0; j + 1 < n; j++)
        {
            var cos = Math.Abs(x[3 * (j + 1)] - x[3 * j]) / scenario.RodLength;
            Assert.Equal(rest.HorizontalTension, rods.GetTension(j) * cos, 1e-5);
        }
    }

    [Theory]
    [InlineData(3)]
    [InlineData(11)]
    [InlineData(21)]
    [InlineData(51)]
    public void Under_xpbd_at_the_defaults_it_comes_within_1e_3_with_rods_within_1e_3_of_their_length(int n)
    {
        var scenario = new HangingChainScenario { Particles = n };
        var world = scenario.Build();
        var rods = (RodNetwork)world.Constraints[0];
        var xpbd = new Xpbd();
        var worst = 0.0;
        for (var s = 0; s < 20000; s++)
        {
            world.Step(xpbd, HangingChainScenario.DefaultTimeStep);
            worst = Math.Max(worst, rods.MaxRelativeViolation(world.Positions));
        }

        var distance = scenario.RestShape().MaxDistance(world.Positions);
        Assert.True(distance < 1e-3, $"N = {n}: {distance:E3} m from the catenary");
        Assert.True(worst < 1e-3, $"N = {n}: a rod stretched {worst:E3} of its length");
    }

    [Fact]
    public void The_constraint_forces_hold_every_rods_acceleration_at_zero_for_chains_and_nets()
    {
        // J a + J' v = 0 for each rod, with a the accelerations the world computes: checks the band solve (a chain) and
        // conjugate gradients (a net of rods whose band is too wide), moving and under load.
        foreach (var (world, rods, direct) in new[] { Chain(), Net() })
        {
            Assert.Equal(direct, rods.SolvesDirectly);
            StateMetrics.Run(world, new RungeKutta4(), 1e-3, 50);
            var a = new double[3 * world.Count];
            world.ComputeAccelerations(world.Time, world.Positions, world.Velocities, a);
            var x = world.Positions;
            var v = world.Velocities;
            for (var r = 0; r < rods.Count; r++)
            {
                var (first, second) = rods.GetEnds(r);
                double acceleration = 0;
                for (var c = 0; c < 3; c++)
                {
                    var d = x[(3 * first) + c] - x[(3 * second) + c];
                    var e = v[(3 * first) + c] - v[(3 * second) + c];
                    acceleration += (d * (a[(3 * first) + c] - a[(3 * second) + c])) + (e * e);
                }

                Assert.True(Math.Abs(acceleration) < 1e-9, $"rod {r}: C'' = {acceleration:E3}");
            }

            Assert.True(rods.MaxRelativeViolation(world.Positions) < 1e-9);
        }
    }

    private static (ParticleWorld, RodNetwork, bool) Chain()
    {
        var world = new HangingChainScenario { Particles = 15 }.Build();
        return (world, (RodNetwork)world.Constraints[0], true);
    }

    private static (ParticleWorld, RodNetwork, bool) Net()
    {
        // A 16 x 16 net of rods hanging from a corner: rods along rows and columns, half-bandwidth 31 in this order.
        const int side = 16;
        var world = new ParticleWorld();
        for (var row = 0; row < side; row++)
        {
            for (var col = 0; col < side; col++)
            {
                world.AddParticle(new Vector3d(col * 0.05, 0, row * 0.05), 0.01);
            }
        }

        // One pinned corner: a straight line of rods between two pins at their full length could not sag at all.
        world.Pin(0);
        world.AddForce(new Forces.Gravity());
        var rods = new RodNetwork(world);
        for (var row = 0; row < side; row++)
        {
            for (var col = 0; col < side; col++)
            {
                var i = (row * side) + col;
                if (col + 1 < side)
                {
                    rods.AddRod(i, i + 1, 0.05);
                }

                if (row + 1 < side)
                {
                    rods.AddRod(i, i + side, 0.05);
                }
            }
        }

        world.AddConstraints(rods);
        return (world, rods, false);
    }
}
