using System;
using ParticlePhysics.Numerics;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Tests.Physics;

/// <summary>The discrete catenary, checked against its own definition: equal horizontal tensions, the span, the lengths.</summary>
public class DiscreteCatenaryTests
{
    [Theory]
    [InlineData(3)]
    [InlineData(11)]
    [InlineData(101)]
    [InlineData(1001)]
    public void Every_free_particle_is_in_equilibrium_and_the_chain_spans_D(int n)
    {
        var scenario = new HangingChainScenario { Particles = n };
        var shape = scenario.RestShape();
        var x = shape.Positions.ToArray();
        var l = scenario.RodLength;
        var m = scenario.Mass / n;
        var h = shape.HorizontalTension;
        Assert.Equal(-0.75, x[0], 1e-15);
        Assert.Equal(0.75, x[3 * (n - 1)], 1e-11);
        Assert.Equal(0, x[(3 * (n - 1)) + 1], 1e-11);
        for (var j = 0; j + 1 < n; j++)
        {
            double dx = x[3 * (j + 1)] - x[3 * j], dy = x[(3 * (j + 1)) + 1] - x[(3 * j) + 1];
            Assert.Equal(l, Math.Sqrt((dx * dx) + (dy * dy)), 1e-13);
        }

        // Particle i between rods i - 1 and i: tension T = H / cos(phi) along each rod; the sum with gravity is 0.
        for (var i = 1; i + 1 < n; i++)
        {
            double fx = 0, fy = -m * scenario.Gravity;
            foreach (var other in new[] { i - 1, i + 1 })
            {
                double dx = x[3 * other] - x[3 * i], dy = x[(3 * other) + 1] - x[(3 * i) + 1];
                var tension = h * l / Math.Abs(dx);
                fx += tension * dx / l;
                fy += tension * dy / l;
            }

            Assert.Equal(0, fx, 1e-10);
            Assert.Equal(0, fy, 1e-10);
        }
    }

    [Fact]
    public void Safeguarded_newton_finds_roots_where_plain_newton_would_leave_the_bracket()
    {
        // atan has a root at 0 where Newton from far away overshoots and diverges.
        Assert.Equal(0, SafeguardedNewton.Root(s => (Math.Atan(s), 1 / (1 + (s * s))), -3, 20), 1e-14);
        Assert.Equal(Math.Sqrt(2), SafeguardedNewton.Root(s => ((s * s) - 2, 2 * s), 0, 10), 1e-15);
        Assert.Throws<ArgumentException>(() => SafeguardedNewton.Root(s => ((s * s) + 1, 2 * s), -1, 1));
    }

    [Fact]
    public void Bad_chains_are_refused()
    {
        Assert.Throws<ArgumentOutOfRangeException>(() => new HangingChainScenario { Particles = 10 });
        Assert.Throws<ArgumentOutOfRangeException>(() => new HangingChainScenario { Particles = 1003 });
        Assert.Throws<ArgumentOutOfRangeException>(() => new HangingChainScenario { Particles = 1 });
        Assert.Throws<ArgumentException>(() => new HangingChainScenario { Span = 2 }.Build());
        Assert.Throws<ArgumentOutOfRangeException>(() => new HangingChainScenario { Gravity = 0 }.RestShape());
    }
}
