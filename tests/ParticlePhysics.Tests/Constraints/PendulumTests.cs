using System;
using ParticlePhysics.Constraints;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Constraints;

/// <summary>
/// The pendulum on a hard rod against Jacobi's sn solution: the rod's tension as a constraint force keeps every
/// integrator's order, and the projection after each step keeps the length.
/// </summary>
public class PendulumTests
{
    [Theory]
    [InlineData(90.0)]
    [InlineData(120.0)]
    public void Rk4_follows_the_exact_angle_within_1e_6_rad_over_several_periods(double angle)
    {
        var scenario = new PendulumScenario { Angle = angle };
        var world = scenario.Build();
        var rods = (RodNetwork)world.Constraints[0];
        var rk4 = new RungeKutta4();
        const double dt = 1e-3;
        var steps = (int)Math.Ceiling(4 * scenario.Period / dt);
        double worstAngle = 0, worstLength = 0;
        for (var s = 1; s <= steps; s++)
        {
            world.Step(rk4, dt);
            var exact = scenario.ExactAngle(s * dt).Angle;
            worstAngle = Math.Max(worstAngle, Math.Abs(PendulumScenario.AngleOf(world.GetPosition(0)) - exact));
            worstLength = Math.Max(worstLength, rods.MaxRelativeViolation(world.Positions));
        }

        Assert.True(worstAngle < 1e-6, $"angle error {worstAngle:E3} rad");
        Assert.True(worstAngle < 1e-9, $"angle error {worstAngle:E3} rad: measured 1.1e-10 at 90 degrees, 2.2e-10 at 120");
        Assert.True(worstLength < 1e-9, $"length drift {worstLength:E3} of L");
    }

    [Theory]
    [InlineData("explicit-euler", 1)]
    [InlineData("semi-implicit-euler", 1)]
    [InlineData("implicit-euler", 1)]
    [InlineData("velocity-verlet", 2)]
    [InlineData("rk4", 4)]
    [InlineData("xpbd", 1)]
    public void Every_integrator_keeps_its_order_on_the_pendulum(string integrator, int order)
    {
        foreach (var angle in new[] { 90.0, 120.0 })
        {
            var scenario = new PendulumScenario { Angle = angle };
            var coarse = StateMetrics.ErrorAt(scenario.Build, scenario, integrator, 0.0025, 2);
            var fine = StateMetrics.ErrorAt(scenario.Build, scenario, integrator, 0.00125, 2);
            var observed = Math.Log2(coarse / fine);
            Assert.True(Math.Abs(observed - order) < 0.15, $"{integrator} at {angle} degrees: observed order {observed:F3}, expected {order}");
        }
    }

    [Theory]
    [InlineData("explicit-euler")]
    [InlineData("semi-implicit-euler")]
    [InlineData("implicit-euler")]
    [InlineData("velocity-verlet")]
    [InlineData("rk4")]
    [InlineData("rk45")]
    [InlineData("xpbd")]
    public void The_rod_keeps_its_length_within_1e_9_under_every_integrator(string integrator)
    {
        var scenario = new PendulumScenario { Angle = 120 };
        var world = scenario.Build();
        var rods = (RodNetwork)world.Constraints[0];
        var stepper = IntegratorCatalog.Create(integrator);
        var worst = 0.0;
        for (var s = 0; s < 2000; s++)
        {
            world.Step(stepper, 0.005);
            worst = Math.Max(worst, rods.MaxRelativeViolation(world.Positions));
        }

        Assert.True(worst < 1e-9, $"{integrator}: length drift {worst:E3} of L");
    }

    [Fact]
    public void The_energy_drift_is_bounded_and_shrinks_with_the_order()
    {
        // Over 20 s (8 periods), RK4's energy error stays at its truncation level, Verlet's oscillates but is bounded.
        var scenario = new PendulumScenario();
        foreach (var (integrator, bound) in new[] { ("rk4", 1e-7), ("velocity-verlet", 1e-3) })
        {
            var world = scenario.Build();
            var stepper = IntegratorCatalog.Create(integrator);
            var start = world.KineticEnergy() + world.PotentialEnergy();
            var worst = 0.0;
            for (var s = 0; s < 10000; s++)
            {
                world.Step(stepper, 0.002);
                worst = Math.Max(worst, Math.Abs(world.KineticEnergy() + world.PotentialEnergy() - start));
            }

            Assert.True(worst < bound, $"{integrator}: energy drift {worst:E3} J over 20 s");
        }
    }

    [Fact]
    public void The_tension_is_the_centripetal_force_plus_the_weights_component()
    {
        // T = m (g cos theta + L theta'^2), an independent oracle for the constraint force.
        var scenario = new PendulumScenario { Angle = 120, Mass = 2, Length = 0.8 };
        var world = scenario.Build();
        var rods = (RodNetwork)world.Constraints[0];
        var rk4 = new RungeKutta4();
        for (var s = 1; s <= 1500; s++)
        {
            world.Step(rk4, 1e-3);
            if (s % 100 != 0)
            {
                continue;
            }

            _ = world.AccumulateForces(world.Time, world.Positions, world.Velocities);
            var (theta, rate) = scenario.ExactAngle(world.Time);
            var expected = scenario.Mass * ((scenario.Gravity * Math.Cos(theta)) + (scenario.Length * rate * rate));
            Assert.Equal(expected, rods.GetTension(0), 1e-6);
        }
    }

    [Fact]
    public void Drift_feedback_keeps_the_solution_and_its_order()
    {
        // The feedback terms vanish on the exact solution, so ks and kd change RK4's error only at its own order.
        var scenario = new PendulumScenario();
        double ErrorWithFeedback(double dt)
        {
            var world = scenario.Build();
            var rods = (RodNetwork)world.Constraints[0];
            rods.DriftStiffness = 100;
            rods.DriftDamping = 20;
            StateMetrics.Run(world, new RungeKutta4(), dt, (int)Math.Round(2 / dt));
            var exact = new double[6];
            scenario.ExactState(2, exact);
            return StateMetrics.MaxAbsError(world.State, exact);
        }

        var coarse = ErrorWithFeedback(0.005);
        var fine = ErrorWithFeedback(0.0025);
        Assert.True(coarse < 1e-6, $"error {coarse:E3}");
        Assert.InRange(Math.Log2(coarse / fine), 3.7, 4.3);
    }

    [Fact]
    public void Bad_rods_and_angles_are_refused()
    {
        var world = new ParticleWorld();
        world.AddParticle(Vector3d.Zero, 1);
        world.AddParticle(new Vector3d(1, 0, 0), 1);
        var rods = new RodNetwork(world);
        Assert.Throws<ArgumentOutOfRangeException>(() => rods.AddRod(0, 2, 1));
        Assert.Throws<ArgumentOutOfRangeException>(() => rods.AddRod(0, -1, 1));
        Assert.Throws<ArgumentException>(() => rods.AddRod(1, 1, 1));
        Assert.Throws<ArgumentOutOfRangeException>(() => rods.AddRod(0, 1, 0));
        Assert.Throws<ArgumentOutOfRangeException>(() => rods.AddCable(0, 1, double.NaN));
        Assert.Throws<ArgumentOutOfRangeException>(() => rods.AddAnchoredRod(0, new Vector3d(double.PositiveInfinity, 0, 0), 1));
        Assert.Throws<ArgumentOutOfRangeException>(() => rods.GetLength(0));
        Assert.Equal(0, rods.Count);
        Assert.Throws<ArgumentOutOfRangeException>(() => new PendulumScenario { Angle = 180 });
        Assert.Throws<ArgumentOutOfRangeException>(() => new PendulumScenario { Angle = 0 });
        Assert.Throws<InvalidOperationException>(() => new PendulumScenario { Drag = 0.1 }.ExactAngle(1));
    }
}
