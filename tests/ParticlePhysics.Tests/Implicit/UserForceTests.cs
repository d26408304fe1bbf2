using System;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Implicit;

/// <summary>
/// A force written by a user, without a Jacobian, in an implicit step: treated explicitly by default, or linearised
/// by finite-difference Jacobian-vector products on request.
/// </summary>
public class UserForceTests
{
    [Fact]
    public void By_default_a_force_without_jacobian_enters_the_step_explicitly()
    {
        // With only that force, implicit Euler becomes v1 = v0 + h F(x0, v0) / m, x1 = x0 + h v1.
        var system = Pair(out var force);
        var h = 0.01;
        var x0 = system.Positions.ToArray();
        var v0 = system.Velocities.ToArray();
        var f0 = system.AccumulateForces(h, x0, v0).ToArray();
        system.Step(new ImplicitEuler(), h);
        for (var k = 0; k < 6; k++)
        {
            var v1 = v0[k] + (h * f0[k] * system.InverseMasses[k / 3]);
            Assert.Equal(v1, system.Velocities[k], 14);
            Assert.Equal(x0[k] + (h * v1), system.Positions[k], 14);
        }

        Assert.NotNull(force);
    }

    [Fact]
    public void Finite_difference_treatment_matches_the_built_in_jacobian()
    {
        // The same zero-rest-length spring, once as the built-in generator and once as a user force without a Jacobian.
        var builtIn = Pair(out _, userWritten: false);
        var user = Pair(out _, userWritten: true);
        var exact = new ImplicitEuler { Tolerance = 1e-12 };
        var byDifferences = new ImplicitEuler { Tolerance = 1e-12, UserForces = UserForceTreatment.FiniteDifference };
        for (var step = 0; step < 50; step++)
        {
            builtIn.Step(exact, 0.05);
            user.Step(byDifferences, 0.05);
        }

        Assert.True(StateMetrics.MaxAbsError(user.State, builtIn.State) < 1e-6);
    }

    [Fact]
    public void A_stiff_user_force_is_stable_at_large_steps_only_when_linearised()
    {
        // omega = sqrt(k / m) = 100 rad/s, h = 0.05: h omega = 5, far past any explicit limit.
        var explicitTreatment = Pair(out _, userWritten: true, stiffness: 10_000);
        var linearised = Pair(out _, userWritten: true, stiffness: 10_000);
        var byDifferences = new ImplicitEuler { UserForces = UserForceTreatment.FiniteDifference };
        StateMetrics.Run(linearised, byDifferences, 0.05, 200);
        var relative = (linearised.GetVelocity(0) - linearised.GetVelocity(1)).Length;
        Assert.True(relative < 1e-6, $"backward Euler damps the stiff oscillation away; relative speed {relative}");
        Assert.Throws<SimulationDivergedException>(() => StateMetrics.Run(explicitTreatment, new ImplicitEuler(), 0.05, 200));
    }

    private static ParticleWorld Pair(out IForceGenerator force, bool userWritten = true, double stiffness = 30)
    {
        var system = new ParticleWorld();
        system.AddParticle(new Vector3d(0, 0, 0), new Vector3d(0.3, 0, -0.2), 1.0);
        system.AddParticle(new Vector3d(1, 0.5, 0), new Vector3d(-0.1, 0.4, 0), 1.0);
        if (userWritten)
        {
            force = new UserSpring(stiffness);
        }
        else
        {
            var springs = new ZeroLengthSprings(system);
            springs.Add(0, 1, stiffness);
            force = springs;
        }

        system.AddForce(force);
        return system;
    }

    /// <summary>A zero-rest-length spring between particles 0 and 1, written as a user would: no Jacobian.</summary>
    private sealed class UserSpring : IForceGenerator
    {
        private readonly double _k;

        public UserSpring(double k) => _k = k;

        public void AddForces(in ParticleState state, Span<double> forces)
        {
            for (var c = 0; c < 3; c++)
            {
                var f = -_k * (state.Positions[c] - state.Positions[3 + c]);
                forces[c] += f;
                forces[3 + c] -= f;
            }
        }
    }
}
