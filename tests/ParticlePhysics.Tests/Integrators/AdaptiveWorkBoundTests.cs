using System;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Snapshots;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Integrators;

/// <summary>
/// Issue 10, item 2: rk45's work is bounded. A tolerance below 100 machine epsilons is refused; a call takes at most
/// MaxStepsPerCall internal steps and fails with a clear SolverNotConvergedException that leaves the world and the
/// integrator as they were. (Before, each of these cases ran for hours: the tests count evaluations and stop a run
/// that passes a million, so that they fail rather than hang.)
/// </summary>
public class AdaptiveWorkBoundTests
{
    private const long EvaluationCap = 1_000_000;

    [Theory]
    [InlineData(1e-300)]
    [InlineData(1e-15)]
    [InlineData(2.2e-14)]
    public void A_tolerance_below_100_machine_epsilons_is_refused(double tolerance)
    {
        var rk45 = new DormandPrince45();
        var e = Assert.Throws<ArgumentOutOfRangeException>("Tolerance", () => rk45.Tolerance = tolerance);
        Assert.Contains("2.220446049250313E-14", e.Message, StringComparison.Ordinal);
        Assert.Equal(1e-8, rk45.Tolerance);
        Assert.Throws<ArgumentOutOfRangeException>(() => new DormandPrince45(tolerance));
        rk45.Tolerance = DormandPrince45.MinTolerance;
    }

    [Theory]
    [InlineData("free-fall", 1e300, DormandPrince45.DefaultMaxStepsPerCall)] // drag limits an explicit step to ~3 s: 3e299 steps
    [InlineData("cloth", 1e6, 1000)] // the springs limit it to ~0.01 s: 1e8 steps (a lower bound keeps the test short)
    public void An_interval_that_needs_too_many_internal_steps_fails_clearly_and_changes_nothing(string scenario, double dt, int bound)
    {
        var world = scenario == "cloth" ? new ClothScenario().Build() : new FreeFallScenario().Build();
        var counter = new EvaluationCounter();
        world.AddForce(counter);
        var rk45 = new DormandPrince45 { MaxStepsPerCall = bound };
        world.Step(rk45, 0.001);
        var before = SimulationSnapshot.Capture(world, rk45);
        counter.Count = 0;

        var e = Assert.Throws<SolverNotConvergedException>(() => world.Step(rk45, dt));
        Assert.Contains($"more than {bound} internal steps", e.Message, StringComparison.Ordinal);
        Assert.InRange(counter.Count, 1, (7 * bound) + 8);
        var after = SimulationSnapshot.Capture(world, rk45);
        Assert.Equal(before.Time, after.Time);
        Assert.Equal(StateMetrics.BitHash(before.State), StateMetrics.BitHash(after.State));
        Assert.Equal(before.IntegratorState[0], after.IntegratorState[0]);
    }

    [Fact]
    public void A_particle_made_a_billion_times_lighter_cannot_make_one_frame_take_unbounded_work()
    {
        // The fuzzer's case: a snapshot with one mass bit flipped made one 1/60 s step take over 200,000 evaluations.
        var world = new ClothScenario().Build();
        var counter = new EvaluationCounter();
        world.AddForce(counter);
        world.SetMass(60, world.GetMass(60) * 1e-12);
        var rk45 = new DormandPrince45 { MaxStepsPerCall = 2000 };
        Assert.Throws<SolverNotConvergedException>(() => world.Step(rk45, 1.0 / 60));
        Assert.InRange(counter.Count, 1, (7 * 2000) + 8);
        Assert.Equal(0.0, world.Time);
    }

    [Fact]
    public void The_bound_is_a_setting_and_ordinary_intervals_stay_far_below_it()
    {
        var rk45 = new DormandPrince45();
        Assert.Equal(10_000, rk45.MaxStepsPerCall);
        Assert.Throws<ArgumentOutOfRangeException>("MaxStepsPerCall", () => rk45.MaxStepsPerCall = 0);
        var world = new ClothScenario().Build();
        StateMetrics.Run(world, rk45, 1.0 / 60, 30);
        Assert.True(rk45.AcceptedSteps + rk45.RejectedSteps < 30 * 100, $"{rk45.AcceptedSteps} accepted steps for half a second");
    }

    /// <summary>Counts evaluations, and stops a run that would otherwise go on for hours.</summary>
    private sealed class EvaluationCounter : IForceGenerator
    {
        public long Count { get; set; }

        public void AddForces(in ParticleState state, Span<double> forces)
        {
            if (++Count > EvaluationCap)
            {
                throw new InvalidOperationException($"more than {EvaluationCap} evaluations for one step");
            }
        }
    }
}
