using System;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Support;
using Xunit.Abstractions;

namespace ParticlePhysics.Tests.Integrators;

/// <summary>
/// Observed orders of convergence, log2(e(dt) / e(dt/2)), over three halvings of dt, on problems with exact
/// solutions. One problem (a time-dependent drive, and the scalar ODE) catches stages evaluated at the wrong time.
/// </summary>
public class ConvergenceOrderTests
{
    private readonly ITestOutputHelper _output;

    public ConvergenceOrderTests(ITestOutputHelper output) => _output = output;

    [Theory]
    [InlineData("explicit-euler", 1, 0.1, 0.01)]
    [InlineData("semi-implicit-euler", 1, 0.1, 0.01)]
    [InlineData("velocity-verlet", 2, 0.1, 0.05)]
    [InlineData("rk4", 4, 0.15, 0.1)]
    public void Damped_oscillator_with_drag(string integrator, double order, double tolerance, double dt)
    {
        var scenario = new MassSpringDamperScenario { Damping = 0.3, Y0 = 1, V0 = 0.5 };
        var orders = StateMetrics.ObservedOrders(
            h => StateMetrics.ErrorAt(scenario.Build, scenario, integrator, h, 4), dt, 4);
        AssertOrders(integrator, orders, order, tolerance);
    }

    [Theory]
    [InlineData("explicit-euler", 1, 0.1, 0.01)]
    [InlineData("semi-implicit-euler", 1, 0.1, 0.01)]
    [InlineData("velocity-verlet", 2, 0.1, 0.05)]
    [InlineData("rk4", 4, 0.15, 0.025)]
    public void Two_mass_chain(string integrator, double order, double tolerance, double dt)
    {
        var scenario = new TwoMassChainScenario();
        var orders = StateMetrics.ObservedOrders(
            h => StateMetrics.ErrorAt(scenario.Build, scenario, integrator, h, 2), dt, 4);
        AssertOrders(integrator, orders, order, tolerance);
    }

    [Theory]
    [InlineData("explicit-euler", 1, 0.1, 0.01)]
    [InlineData("semi-implicit-euler", 1, 0.1, 0.01)]
    [InlineData("velocity-verlet", 2, 0.1, 0.05)]
    [InlineData("rk4", 4, 0.15, 0.1)]
    public void Time_dependent_drive(string integrator, double order, double tolerance, double dt)
    {
        var drive = new HarmonicDrive(amplitude: 2.0, angularFrequency: 3.0);
        double Error(double h)
        {
            var system = new ParticleWorld();
            system.AddParticle(new Vector3d(0.5, 0, 0), new Vector3d(-1, 0, 0), 2.0);
            system.AddForce(drive);
            var steps = (int)Math.Round(2.0 / h);
            StateMetrics.Run(system, IntegratorCatalog.Create(integrator), h, steps);
            var expected = new double[6];
            drive.ExactState(0.5, -1, steps * h, expected);
            return StateMetrics.MaxAbsError(system.State, expected);
        }

        AssertOrders(integrator, StateMetrics.ObservedOrders(Error, dt, 4), order, tolerance);
    }

    [Theory]
    [InlineData("explicit-euler", 1, 0.1, 0.01)]
    [InlineData("rk4", 4, 0.15, 0.05)]
    public void Scalar_ode_with_time_dependent_right_hand_side(string integrator, double order, double tolerance, double dt)
    {
        var ode = new GaussianDecayOde();
        double Error(double h)
        {
            var simulation = new OdeSimulation(ode, new[] { 1.0 });
            var method = IntegratorCatalog.Create(integrator);
            var steps = (int)Math.Round(2.0 / h);
            for (var s = 0; s < steps; s++)
            {
                simulation.Step(method, h);
            }

            return Math.Abs(simulation.State[0] - Math.Exp(-Math.Pow(steps * h, 2)));
        }

        AssertOrders(integrator, StateMetrics.ObservedOrders(Error, dt, 4), order, tolerance);
    }

    private void AssertOrders(string integrator, double[] orders, double expected, double tolerance)
    {
        _output.WriteLine($"{integrator}: observed orders {string.Join(", ", Array.ConvertAll(orders, o => o.ToString("F3")))}");
        Assert.Equal(3, orders.Length);
        foreach (var observed in orders)
        {
            Assert.InRange(observed, expected - tolerance, expected + tolerance);
        }
    }
}
