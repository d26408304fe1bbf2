using System;
using System.Collections.Generic;
using System.Linq;
using ParticlePhysics.Contacts;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Tests.Contacts;

/// <summary>
/// The bouncing ball against its exact solution: apex heights R + e^(2n) (h - R), impact times, rest after
/// T = t1 (1 + e) / (1 - e), horizontal friction per impact.
/// </summary>
public class BouncingBallTests
{
    [Theory]
    [InlineData("rk4", 1e-12)]
    [InlineData("velocity-verlet", 1e-12)]
    [InlineData("rk45", 1e-10)]
    public void Apex_heights_and_impact_times_match_the_exact_ones_under_the_integrators_exact_for_a_parabola(
        string integrator, double tolerance)
    {
        // The issue asks 1e-3 relative at the default dt under RK4; a ballistic path is a parabola that RK4, velocity
        // Verlet and RK45 integrate exactly, and the contact search finds impacts on it exactly, so they meet ~1e-14.
        var scenario = new BouncingBallScenario();
        var run = Bounces.Record(scenario, integrator, BouncingBallScenario.DefaultTimeStep, BouncingBallScenario.DefaultDuration);
        Assert.True(run.Apexes.Count >= 20, $"only {run.Apexes.Count} bounces");
        for (var n = 1; n <= 20; n++)
        {
            Assert.True(Relative(run.Apexes[n - 1], scenario.ApexHeight(n)) < tolerance, $"apex {n}: {run.Apexes[n - 1]:R} vs {scenario.ApexHeight(n):R}");
            Assert.True(Relative(run.Impacts[n - 1], scenario.ImpactTime(n)) < tolerance, $"impact {n}: {run.Impacts[n - 1]:R} vs {scenario.ImpactTime(n):R}");
        }
    }

    [Theory]
    [InlineData("semi-implicit-euler")]
    [InlineData("explicit-euler")]
    [InlineData("implicit-euler")]
    public void First_order_integrators_bounce_to_within_their_own_error(string integrator)
    {
        // Their free flight is itself wrong by O(dt); the contact stage adds no error of its own on top.
        var scenario = new BouncingBallScenario();
        var run = Bounces.Record(scenario, integrator, 0.001, 5);
        for (var n = 1; n <= 10; n++)
        {
            Assert.True(Relative(run.Apexes[n - 1], scenario.ApexHeight(n)) < 0.05, $"apex {n}");
        }
    }

    [Theory]
    [InlineData(0.001)]
    [InlineData(0.00123)]
    [InlineData(1.0 / 60.0)]
    public void Results_do_not_depend_on_where_an_impact_falls_in_a_step(double dt)
    {
        var scenario = new BouncingBallScenario { Radius = 0.1, Height = 2 };
        var run = Bounces.Record(scenario, "rk4", dt, 6);
        for (var n = 1; n <= 8; n++)
        {
            Assert.True(Relative(run.Apexes[n - 1], scenario.ApexHeight(n)) < 1e-12, $"dt {dt}: apex {n}");
            Assert.True(Relative(run.Impacts[n - 1], scenario.ImpactTime(n)) < 1e-12, $"dt {dt}: impact {n}");
        }
    }

    [Fact]
    public void After_the_last_bounce_the_ball_rests_on_the_ground_without_jitter()
    {
        var scenario = new BouncingBallScenario { Radius = 0.05 };
        var world = scenario.Build();
        var rk4 = new RungeKutta4();
        var steps = (int)Math.Round(5 / 0.001);
        var restStep = (int)Math.Ceiling(scenario.RestTime / 0.001);
        for (var step = 1; step <= steps; step++)
        {
            world.Step(rk4, 0.001);
            if (step > restStep)
            {
                Assert.Equal(0.05, world.GetPosition(0).Y);
                Assert.True(Math.Abs(world.GetVelocity(0).Y) < 1e-3, $"vy {world.GetVelocity(0).Y} at step {step}");
            }
        }

        Assert.Equal(0.0, world.GetVelocity(0).Y);
    }

    [Fact]
    public void The_bounces_stop_when_the_rebound_falls_below_the_resting_speed_just_before_T()
    {
        // The exact train of bounces is endless; the rebounds below RestingSpeed (0.01 m/s) that are left would have
        // flown 2 w / (g (1 - e)) in all, which is how early the ball comes to rest.
        var scenario = new BouncingBallScenario();
        var run = Bounces.Record(scenario, "rk4", 0.001, 5);
        var rebound = ContactSet.DefaultRestingSpeed;
        var missing = 2 * rebound / (scenario.Gravity * (1 - scenario.Restitution));
        Assert.InRange(run.RestTime, scenario.RestTime - missing, scenario.RestTime);
    }

    [Theory]
    [InlineData(0.1, 1.0)]
    [InlineData(0.3, 0.5)]
    [InlineData(0.05, 8.0)]
    public void Each_impact_takes_mu_1_plus_e_u_off_the_horizontal_speed_then_rest_slides_to_a_stop(double mu, double vx0)
    {
        var scenario = new BouncingBallScenario { Friction = mu, Vx0 = vx0 };
        var world = scenario.Build();
        var rk4 = new RungeKutta4();
        var exact = new double[6];
        for (var step = 1; step <= 5000; step++)
        {
            world.Step(rk4, 0.001);
            scenario.ExactState(step * 0.001, exact);
            var t = step * 0.001;
            if (t < scenario.RestTime - 0.05)
            {
                Assert.True(Math.Abs(world.GetVelocity(0).X - exact[3]) < 1e-9, $"vx at t = {t}: {world.GetVelocity(0).X} vs {exact[3]}");
                Assert.True(Math.Abs(world.GetPosition(0).X - exact[0]) < 1e-9, $"x at t = {t}");
            }
        }

        // Resting from just before T on, it decelerates at mu g: it stops where the exact ball stops, to within the
        // slide over the short stretch it rests early.
        scenario.ExactState(5, exact);
        Assert.Equal(exact[3], world.GetVelocity(0).X, 12);
        Assert.True(Math.Abs(world.GetPosition(0).X - exact[0]) < 2e-3 * Math.Max(1, vx0), $"x {world.GetPosition(0).X} vs {exact[0]}");
    }

    private static double Relative(double actual, double expected) => Math.Abs(actual - expected) / Math.Abs(expected);
}

/// <summary>A bouncing ball's run: each apex (from the state before it, exactly for a ballistic flight), each impact time the contact set reports.</summary>
internal sealed record Bounces(List<double> Apexes, List<double> Impacts, double RestTime)
{
    public static Bounces Record(BouncingBallScenario scenario, string integrator, double dt, double duration, Action<ContactSet>? ground = null)
    {
        var world = scenario.Build();
        var contacts = world.Constraints.OfType<ContactSet>().Single();
        ground?.Invoke(contacts);
        var stepper = IntegratorCatalog.Create(integrator);
        var apexes = new List<double>();
        var impacts = new List<double>();
        var rest = double.NaN;
        var steps = (int)Math.Round(duration / dt);
        for (var step = 0; step < steps; step++)
        {
            var y = world.GetPosition(0).Y;
            var vy = world.GetVelocity(0).Y;
            world.Step(stepper, dt);
            foreach (var impact in contacts.Impacts)
            {
                if (!impact.Resting)
                {
                    impacts.Add(impact.Time);
                }
                else if (double.IsNaN(rest))
                {
                    rest = impact.Time;
                }
            }

            if (vy > 0 && world.GetVelocity(0).Y <= 0 && contacts.ImpactCount == 0)
            {
                apexes.Add(y + (vy * vy / (2 * scenario.Gravity))); // the top of the parabola through the state before
            }
        }

        return new Bounces(apexes, impacts, rest);
    }
}
