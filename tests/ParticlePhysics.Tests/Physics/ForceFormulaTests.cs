using System;
using ParticlePhysics.Forces;

namespace ParticlePhysics.Tests.Physics;

/// <summary>
/// Each force generator against its formula in SCENARIOS.md, computed by hand for chosen configurations,
/// with Newton's third law, and each potential energy against the force by central differences (-dU/dx = F).
/// </summary>
public class ForceFormulaTests
{
    [Fact]
    public void Gravity_is_m_g_down()
    {
        var system = new ParticleWorld();
        system.AddParticle(new Vector3d(1, 2, 3), 0.5);
        system.AddParticle(new Vector3d(0, 0, 0), 2.0);
        system.AddForce(new Gravity());
        var f = Forces(system);
        Assert.Equal(new[] { 0, -0.5 * 9.81, 0, 0, -2 * 9.81, 0 }, f);
    }

    [Fact]
    public void Linear_drag_is_minus_lambda_v_and_acts_only_on_its_particles()
    {
        var system = new ParticleWorld();
        system.AddParticle(Vector3d.Zero, new Vector3d(1, -2, 3), 1);
        system.AddParticle(Vector3d.Zero, new Vector3d(4, 5, 6), 1);
        system.AddForce(new LinearDrag(0.5, system, new[] { 1 }));
        Assert.Equal(new[] { 0, 0, 0, -2, -2.5, -3 }, Forces(system));
        system.AddForce(new LinearDrag(0.1));
        Assert.Equal(new[] { -0.1, 0.2, -0.30000000000000004, -2.4, -3, -3.6 }, Forces(system));
    }

    [Fact]
    public void Zero_rest_length_spring_is_minus_k_times_the_separation()
    {
        var system = new ParticleWorld();
        system.AddParticle(new Vector3d(1, 2, 3), 1);
        system.AddParticle(new Vector3d(-1, 0, 1), 1);
        var springs = new ZeroLengthSprings(system);
        springs.Add(0, 1, 2.0);
        springs.AddAnchored(1, new Vector3d(0, 0, 1), 3.0);
        system.AddForce(springs);
        // Pair: -2 (2, 2, 2) on particle 0, the opposite on 1; anchor: -3 (-1, 0, 0) on particle 1.
        Assert.Equal(new[] { -4.0, -4, -4, 4 + 3, 4, 4 }, Forces(system));
    }

    [Fact]
    public void Spring_with_rest_length_and_axial_damping_follows_the_contract_formula()
    {
        var system = new ParticleWorld();
        system.AddParticle(new Vector3d(3, 0, 0), new Vector3d(1, 2, 0), 1);
        system.AddParticle(new Vector3d(0, 4, 0), new Vector3d(0, 0, 5), 1);
        var springs = new SpringNetwork(system);
        springs.Add(0, 1, stiffness: 10, restLength: 2, damping: 0.5);
        system.AddForce(springs);

        // d = (3, -4, 0), l = 5, u = (0.6, -0.8, 0); (v_i - v_j) . u = (1, 2, -5) . u = 0.6 - 1.6 = -1.
        // F_i = -(10 (5 - 2) + 0.5 (-1)) u = -29.5 u.
        var f = Forces(system);
        var expected = new[] { -29.5 * 0.6, 29.5 * 0.8, 0, 29.5 * 0.6, -29.5 * 0.8, 0 };
        for (var k = 0; k < 6; k++)
        {
            Assert.Equal(expected[k], f[k], 12);
        }
    }

    [Fact]
    public void A_stretched_spring_pulls_its_ends_together_and_a_compressed_one_pushes_them_apart()
    {
        double ForceOnFirstAlongX(double separation)
        {
            var system = new ParticleWorld();
            system.AddParticle(new Vector3d(separation, 0, 0), 1);
            system.AddParticle(Vector3d.Zero, 1);
            var springs = new SpringNetwork(system);
            springs.Add(0, 1, 1, restLength: 1);
            system.AddForce(springs);
            return Forces(system)[0];
        }

        Assert.True(ForceOnFirstAlongX(1.5) < 0, "stretched: particle 0 at +x is pulled back toward -x");
        Assert.True(ForceOnFirstAlongX(0.5) > 0, "compressed: particle 0 is pushed away toward +x");
        Assert.Equal(0, ForceOnFirstAlongX(1.0));
    }

    [Fact]
    public void Axial_damping_opposes_the_rate_of_stretch()
    {
        var system = new ParticleWorld();
        system.AddParticle(new Vector3d(1, 0, 0), new Vector3d(2, 0, 0), 1);
        system.AddParticle(Vector3d.Zero, new Vector3d(0, 0, 0), 1);
        var springs = new SpringNetwork(system);
        springs.Add(0, 1, stiffness: 0, restLength: 1, damping: 0.25);
        system.AddForce(springs);
        Assert.Equal(new[] { -0.5, 0, 0, 0.5, 0, 0 }, Forces(system));
    }

    [Fact]
    public void A_spring_of_zero_length_gives_zero_force_never_nan()
    {
        var system = new ParticleWorld();
        system.AddParticle(new Vector3d(1, 1, 1), new Vector3d(1, 0, 0), 1);
        system.AddParticle(new Vector3d(1, 1, 1), 1);
        var springs = new SpringNetwork(system);
        springs.Add(0, 1, 100, restLength: 0.5, damping: 3);
        springs.AddAnchored(0, new Vector3d(1, 1, 1), 100, 0.5, 3);
        system.AddForce(springs);
        Assert.Equal(new double[6], Forces(system));
    }

    [Fact]
    public void Damper_is_minus_c_times_the_relative_velocity()
    {
        var system = new ParticleWorld();
        system.AddParticle(Vector3d.Zero, new Vector3d(1, 2, 3), 1);
        system.AddParticle(new Vector3d(5, 0, 0), new Vector3d(3, 2, 1), 1);
        var dampers = new Dampers(system);
        dampers.Add(0, 1, 0.5);
        system.AddForce(dampers);
        Assert.Equal(new[] { 1.0, 0, -1, -1, 0, 1 }, Forces(system));
    }

    [Fact]
    public void Potential_energies_are_consistent_with_their_forces()
    {
        var system = new ParticleWorld();
        system.AddParticle(new Vector3d(0.3, -0.2, 0.1), 0.7);
        system.AddParticle(new Vector3d(1.1, 0.4, -0.5), 1.3);
        system.AddParticle(new Vector3d(-0.6, 1.0, 0.2), 0.4);
        var springs = new SpringNetwork(system);
        springs.Add(0, 1, 12, 0.8);
        springs.Add(1, 2, 7, 0.3);
        springs.AddAnchored(2, new Vector3d(0, 2, 0), 5, 0.5);
        var zero = new ZeroLengthSprings(system);
        zero.Add(0, 2, 3);
        zero.AddAnchored(1, new Vector3d(1, 1, 1), 2);
        system.AddForce(springs);
        system.AddForce(zero);
        system.AddForce(new Gravity(new Vector3d(0.5, -9.81, 0.25)));

        var forces = Forces(system);
        const double h = 1e-6;
        var state = system.State.ToArray();
        for (var k = 0; k < 9; k++)
        {
            var original = state[k];
            state[k] = original + h;
            system.SetState(state);
            var plus = system.PotentialEnergy();
            state[k] = original - h;
            system.SetState(state);
            var minus = system.PotentialEnergy();
            state[k] = original;
            system.SetState(state);
            Assert.Equal(forces[k], -(plus - minus) / (2 * h), 5);
        }
    }

    [Fact]
    public void Forces_between_particles_obey_newtons_third_law()
    {
        var cloth = new Scenarios.ClothScenario { Resolution = 0.25, Gravity = 0, Drag = 0 }.Build();
        var random = new Random(3);
        var state = cloth.State.ToArray();
        for (var k = 0; k < state.Length; k++)
        {
            if (k < 3 * cloth.Count || !cloth.IsPinned((k % (3 * cloth.Count)) / 3))
            {
                state[k] += 0.05 * (random.NextDouble() - 0.5);
            }
        }

        cloth.SetState(state);
        var f = Forces(cloth);
        double sx = 0, sy = 0, sz = 0, scale = 0;
        for (var i = 0; i < cloth.Count; i++)
        {
            sx += f[3 * i];
            sy += f[(3 * i) + 1];
            sz += f[(3 * i) + 2];
            scale += Math.Abs(f[3 * i]) + Math.Abs(f[(3 * i) + 1]) + Math.Abs(f[(3 * i) + 2]);
        }

        Assert.True(scale > 1, "the perturbation must produce forces");
        Assert.True(Math.Abs(sx) + Math.Abs(sy) + Math.Abs(sz) < 1e-13 * scale);
    }

    private static double[] Forces(ParticleWorld system) =>
        system.AccumulateForces(system.Time, system.Positions, system.Velocities).ToArray();
}
