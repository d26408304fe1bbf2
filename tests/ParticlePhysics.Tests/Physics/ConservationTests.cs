using System;
using ParticlePhysics.Cloth;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Physics;

/// <summary>Physical invariants: momentum under internal forces, energy behaviour of the Euler variants.</summary>
public class ConservationTests
{
    [Theory]
    [InlineData("explicit-euler")]
    [InlineData("semi-implicit-euler")]
    [InlineData("rk4")]
    [InlineData("velocity-verlet")]
    [InlineData("rk45")]
    public void Springs_and_dampers_alone_conserve_total_momentum(string integrator)
    {
        var cloth = new ClothScenario { Resolution = 0.2, Pinning = ClothPinning.None, Gravity = 0, Drag = 0 };
        var system = cloth.Build();
        var random = new Random(7);
        for (var i = 0; i < system.Count; i++)
        {
            system.SetVelocity(i, new Vector3d(1 + random.NextDouble(), 0.5 - random.NextDouble(), -0.3 + random.NextDouble()));
            system.SetMass(i, 0.01 + (0.05 * random.NextDouble()));
        }

        var extra = new ZeroLengthSprings(system);
        extra.Add(0, system.Count - 1, 3.0);
        extra.Add(2, 17, 1.5);
        var dampers = new Dampers(system);
        dampers.Add(1, 20, 0.2);
        dampers.Add(5, 9, 0.7);
        system.AddForce(extra);
        system.AddForce(dampers);
        for (var i = system.Forces.Count - 1; i >= 0; i--)
        {
            if (system.Forces[i] is LinearDrag or Gravity)
            {
                system.RemoveForce(system.Forces[i]);
            }
        }

        var before = system.TotalMomentum();
        StateMetrics.Run(system, IntegratorCatalog.Create(integrator), 0.002, 250);
        var after = system.TotalMomentum();
        var drift = (after - before).Length / before.Length;
        Assert.True(drift < 1e-12, $"{integrator}: relative momentum drift {drift}");
        Assert.NotEqual(system.Positions[0], cloth.Build().Positions[0]);
    }

    [Fact]
    public void Explicit_euler_pumps_energy_into_an_undamped_oscillator()
    {
        var (system, integrator) = (Oscillator(), new ExplicitEuler());
        var initial = TotalEnergy(system);
        var previous = initial;
        for (var block = 0; block < 100; block++)
        {
            StateMetrics.Run(system, integrator, 0.01, 1000);
            var energy = TotalEnergy(system);
            Assert.True(energy > previous, $"energy fell from {previous} to {energy}");
            previous = energy;
        }

        // Each step multiplies the energy by exactly 1 + (omega dt)^2: after 10^5 steps, e^10 times.
        Assert.Equal(Math.Pow(1 + 1e-4, 1e5), previous / initial, 6);
    }

    [Fact]
    public void Semi_implicit_euler_keeps_the_energy_of_an_undamped_oscillator_bounded_over_100000_steps()
    {
        var (system, integrator) = (Oscillator(), new SemiImplicitEuler());
        var initial = TotalEnergy(system);
        var worst = 0.0;
        for (var step = 0; step < 100_000; step++)
        {
            system.Step(integrator, 0.01);
            worst = Math.Max(worst, Math.Abs(TotalEnergy(system) - initial) / initial);
        }

        // The map conserves a modified energy; the true energy oscillates by O(omega dt) = 1 % and never drifts.
        Assert.True(worst < 0.01, $"worst relative energy deviation {worst}");
    }

    private static ParticleWorld Oscillator()
    {
        var system = new ParticleWorld();
        system.AddParticle(new Vector3d(1, 0, 0), 1.0);
        var spring = new ZeroLengthSprings(system);
        spring.AddAnchored(0, Vector3d.Zero, 1.0);
        system.AddForce(spring);
        return system;
    }

    private static double TotalEnergy(ParticleWorld system) => system.KineticEnergy() + system.PotentialEnergy();
}
