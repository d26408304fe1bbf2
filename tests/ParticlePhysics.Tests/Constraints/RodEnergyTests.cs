using System;
using System.Collections.Generic;
using System.Globalization;
using System.Linq;
using ParticlePhysics.Constraints;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using Xunit.Abstractions;

namespace ParticlePhysics.Tests.Constraints;

/// <summary>
/// Issue 27, item 4: chains of rods released horizontal gained energy without bound under semi-implicit and implicit
/// Euler (a triple pendulum of 0.1 m rods and 0.1 kg masses at 1 ms: up to 1e16 J from the 0.589 J its fall releases,
/// and a failed step at 3.4 s; a double pendulum reached 1,366 J). Rods must be as stable as the integrator they run
/// under: semi-implicit Euler bounded, implicit Euler dissipative.
/// </summary>
public class RodEnergyTests
{
    private const double RodLength = 0.1;
    private const double Mass = 0.1;

    private readonly ITestOutputHelper _output;

    public RodEnergyTests(ITestOutputHelper output)
    {
        _output = output;
    }

    [Theory]
    [InlineData("semi-implicit-euler")]
    [InlineData("implicit-euler")]
    public void Chains_of_2_to_10_rods_stay_as_stable_as_their_integrator_for_5_s(string integrator) =>
        CheckChains(integrator, 5, new[] { 2, 3, 5, 10 }, 1e-3);

    /// <remarks>
    /// Semi-implicit Euler takes the tension explicitly, so it is stable where it would be on springs of the tensions'
    /// geometric stiffness, T / L per rod: h 2 sqrt(T / (m L)) &lt; 2. Measured with rk4 over these 60 s, T reaches
    /// 22 N on two rods and 501 N on ten (2 sqrt(T / (m L)) = 94 and 447 rad/s): 2 ms is within that limit for every
    /// chain (h omega = 0.9 for ten rods), and bounded too. Near it, at 4.2 ms (h omega = 1.9), ten rods gain up to 19 J. Implicit
    /// Euler is stable and dissipative at a game's 60 Hz as well.
    /// </remarks>
    [Theory]
    [Trait("Category", "Long")]
    [InlineData("semi-implicit-euler", 1e-3)]
    [InlineData("semi-implicit-euler", 2e-3)]
    [InlineData("implicit-euler", 1e-3)]
    [InlineData("implicit-euler", 1.0 / 60)]
    public void Chains_of_2_to_10_rods_stay_as_stable_as_their_integrator_for_60_s(string integrator, double dt) =>
        CheckChains(integrator, 60, Enumerable.Range(2, 9), dt);

    /// <summary>
    /// n rods of <see cref="RodLength"/> and n particles of <see cref="Mass"/> in a row along x from an anchor at the
    /// origin, under gravity: released horizontal, the chain falls through m g L n (n + 1) / 2 to hanging straight down.
    /// </summary>
    internal static ParticleWorld Chain(int rods)
    {
        var world = new ParticleWorld();
        for (var i = 1; i <= rods; i++)
        {
            world.AddParticle(new Vector3d(i * RodLength, 0, 0), Mass);
        }

        world.AddForce(new Gravity());
        var network = new RodNetwork(world);
        network.AddAnchoredRod(0, Vector3d.Zero, RodLength);
        for (var i = 1; i < rods; i++)
        {
            network.AddRod(i - 1, i, RodLength);
        }

        world.AddConstraints(network);
        return world;
    }

    /// <summary>The energy the fall from horizontal to hanging releases: m g L n (n + 1) / 2.</summary>
    internal static double Released(int rods) => Mass * Gravity.StandardAcceleration * RodLength * rods * (rods + 1) / 2;

    /// <summary>
    /// Semi-implicit Euler: E - E0 stays within -5 % and +1 % of the released energy per millisecond of step, at every
    /// step: a symplectic method's bounded oscillation, whose amplitude is proportional to h, with dips where the
    /// chain's end whips round (measured over 60 s: at 1 ms from -0.67 % (ten rods) to +0.44 % (two); at 2 ms from
    /// -3.4 % (nine rods) to +0.87 % (two)); before, two rods gained 1,366 J of the 0.294 J released. Implicit Euler: E never rises above E0 beyond rounding, and its mean over each second is at
    /// most the second before's (it dissipates).
    /// </summary>
    private void CheckChains(string integrator, double seconds, IEnumerable<int> chains, double dt)
    {
        var steps = (int)Math.Round(seconds / dt);
        foreach (var rods in chains)
        {
            var world = Chain(rods);
            var method = IntegratorCatalog.Create(integrator);
            var released = Released(rods);
            var start = world.KineticEnergy() + world.PotentialEnergy();
            double highest = double.NegativeInfinity, lowest = double.PositiveInfinity;
            var means = new List<double>();
            var sum = 0.0;
            var perWindow = (int)Math.Round(1 / dt);
            for (var s = 1; s <= steps; s++)
            {
                try
                {
                    world.Step(method, dt);
                }
                catch (SimulationDivergedException e)
                {
                    Assert.Fail($"{integrator}, {rods} rods: the step failed at t = {world.Time:F3} s ({e.Message})");
                }

                var change = world.KineticEnergy() + world.PotentialEnergy() - start;
                highest = Math.Max(highest, change);
                lowest = Math.Min(lowest, change);
                sum += change;
                if (s % perWindow == 0)
                {
                    means.Add(sum / perWindow);
                    sum = 0;
                }
            }

            var rises = means.Zip(means.Skip(1), (a, b) => b - a).DefaultIfEmpty(0).Max();
            _output.WriteLine(string.Create(
                CultureInfo.InvariantCulture,
                $"{integrator} at {dt:G4} s, {rods} rods, {seconds} s: E - E0 from {lowest:E3} to {highest:E3} J (released {released:F3} J), mean over the last second {means[^1]:E3} J, largest rise of a second's mean {rises:E3} J"));
            if (integrator == "semi-implicit-euler")
            {
                // A first-order symplectic method's energy oscillates about E0 with an amplitude proportional to h.
                var perMillisecond = dt / 1e-3 * released;
                Assert.True(
                    highest < 0.01 * perMillisecond && lowest > -0.05 * perMillisecond,
                    $"{rods} rods: E - E0 from {lowest:E3} to {highest:E3} J, the {released:F3} J released, at {dt} s");
            }
            else
            {
                Assert.True(highest < 1e-12 * released, $"{rods} rods: E rose {highest:E3} J above E0");
                Assert.True(rises <= 1e-12 * released, $"{rods} rods: a second's mean energy rose by {rises:E3} J over the one before");
            }
        }
    }
}
