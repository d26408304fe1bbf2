using System;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Integrators;

/// <summary>Each course scenario, integrated with the contract's default dt, against its exact solution.</summary>
public class ExactSolutionAccuracyTests
{
    [Theory]
    [InlineData("rk4", 1e-9)]
    [InlineData("rk45", 1e-6)]
    [InlineData("velocity-verlet", 5e-3)]
    [InlineData("semi-implicit-euler", 0.5)]
    [InlineData("explicit-euler", 0.5)]
    public void Free_fall_with_drag_over_10_s(string integrator, double tolerance)
    {
        var scenario = new FreeFallScenario();
        var error = StateMetrics.ErrorAt(scenario.Build, scenario, integrator, 0.01, 10);
        Assert.True(error < tolerance, $"{integrator}: error {error}");
    }

    [Theory]
    [InlineData("rk4")]
    [InlineData("velocity-verlet")]
    public void Free_fall_without_drag_is_exact_for_second_order_and_higher_methods(string integrator)
    {
        // Constant acceleration: x = h - g t^2 / 2 is reproduced to rounding by any method exact on quadratics.
        var scenario = new FreeFallScenario { Drag = 0 };
        var error = StateMetrics.ErrorAt(scenario.Build, scenario, integrator, 0.01, 10);
        Assert.True(error < 1e-10, $"{integrator}: error {error}");
    }

    [Theory]
    [InlineData(0.1, 1e-8)]
    [InlineData(2.0, 1e-8)]
    [InlineData(5.0, 1e-8)]
    public void Mass_spring_damper_under_critically_and_over_damped_with_rk4(double damping, double tolerance)
    {
        var scenario = new MassSpringDamperScenario { Damping = damping, Y0 = 1, V0 = 0.5 };
        var error = StateMetrics.ErrorAt(scenario.Build, scenario, "rk4", 0.01, 20);
        Assert.True(error < tolerance, $"c={damping}: error {error}");
    }

    [Theory]
    [InlineData(0.0)]
    [InlineData(0.5)]
    public void Two_mass_chain_with_rk4_follows_its_eigenmodes(double restLength2)
    {
        var scenario = new TwoMassChainScenario { RestLength2 = restLength2 };
        var error = StateMetrics.ErrorAt(scenario.Build, scenario, "rk4", 0.01, 20);
        Assert.True(error < 1e-7, $"error {error}");
    }

    [Fact]
    public void Scalar_ode_with_rk4_at_the_course_dt()
    {
        var ode = new GaussianDecayOde();
        var simulation = new OdeSimulation(ode, new[] { GaussianDecayOde.InitialValue });
        var rk4 = new RungeKutta4();
        for (var s = 0; s < 20; s++)
        {
            simulation.Step(rk4, 0.1);
        }

        var error = Math.Abs(simulation.State[0] - Math.Exp(-4));
        Assert.True(error < 2e-5, $"error {error}");
        Assert.True(error > 0, "RK4 is not exact on this problem; a zero error would mean the test measures nothing");
    }

    [Theory]
    [InlineData(1e-6)]
    [InlineData(1e-8)]
    [InlineData(1e-10)]
    public void Rk45_error_stays_within_a_small_factor_of_its_tolerance(double tolerance)
    {
        // The tolerance bounds each internal step's error relative to 1 + |y|; measured globally over a whole run,
        // in the same scaled units, the error must stay within a small factor of it.
        foreach (var (name, build, exact, duration) in Problems())
        {
            var system = build();
            var integrator = new DormandPrince45(tolerance);
            var worst = 0.0;
            var expected = new double[system.Dimension];
            for (var s = 1; s <= (int)duration; s++)
            {
                system.Step(integrator, 1.0);
                exact.ExactState(s, expected);
                for (var i = 0; i < expected.Length; i++)
                {
                    worst = Math.Max(worst, Math.Abs(system.State[i] - expected[i]) / (1 + Math.Abs(expected[i])));
                }
            }

            Assert.True(worst < 20 * tolerance, $"{name}, tolerance {tolerance}: worst scaled error {worst}");
        }
    }

    [Fact]
    public void Rk45_error_shrinks_with_its_tolerance_and_lands_on_output_times()
    {
        var scenario = new MassSpringDamperScenario { Y0 = 1 };
        double Error(double tolerance)
        {
            var system = scenario.Build();
            var rk45 = new DormandPrince45(tolerance);
            for (var s = 0; s < 20; s++)
            {
                system.Step(rk45, 1.0);
            }

            Assert.Equal(20.0, system.Time);
            var expected = new double[6];
            scenario.ExactState(20, expected);
            return StateMetrics.MaxAbsError(system.State, expected);
        }

        var loose = Error(1e-6);
        var tight = Error(1e-10);
        Assert.True(tight < loose / 1000, $"loose {loose}, tight {tight}");
    }

    [Fact]
    public void Rk45_rejects_steps_when_its_first_guess_is_too_large()
    {
        var scenario = new MassSpringDamperScenario { Stiffness = 400, Y0 = 1 };
        var system = scenario.Build();
        var rk45 = new DormandPrince45(1e-8) { CurrentStepSize = 0.5 };
        system.Step(rk45, 1.0);
        Assert.True(rk45.RejectedSteps > 0);
        var expected = new double[6];
        scenario.ExactState(1.0, expected);
        Assert.True(StateMetrics.MaxAbsError(system.State, expected) < 1e-5);
    }

    private static (string Name, Func<ParticleWorld> Build, IExactSolution Exact, double Duration)[] Problems()
    {
        var freeFall = new FreeFallScenario();
        var oscillator = new MassSpringDamperScenario { Y0 = 1 };
        var chain = new TwoMassChainScenario();
        return new (string, Func<ParticleWorld>, IExactSolution, double)[]
        {
            ("free-fall", freeFall.Build, freeFall, 10),
            ("mass-spring-damper", oscillator.Build, oscillator, 20),
            ("two-mass-chain", chain.Build, chain, 20),
        };
    }
}
