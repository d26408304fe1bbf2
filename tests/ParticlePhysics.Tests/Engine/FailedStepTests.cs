using System;
using ParticlePhysics.Cloth;
using ParticlePhysics.Integrators;
using ParticlePhysics.Snapshots;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Engine;

/// <summary>
/// Issue 10, item 4: a rejected step leaves the world and the integrator exactly as they were. After a divergence, a
/// throwing force or a throwing Jacobian, the integrator's state (implicit Euler's warm start, rk45's step size) is
/// what it was before, so a retry equals the same step taken after restoring a snapshot of the last good state.
/// </summary>
public class FailedStepTests
{
    private const double Dt = 1.0 / 60;

    public static TheoryData<string, string> Cases()
    {
        var data = new TheoryData<string, string>();
        foreach (var integrator in new[] { "implicit-euler", "implicit-euler-fd", "rk45", "rk4", "velocity-verlet" })
        {
            foreach (var failure in new[] { "diverges", "force-throws-first", "force-throws-later", "force-writes-nan" })
            {
                data.Add(integrator, failure);
            }
        }

        data.Add("implicit-euler", "jacobian-throws");
        data.Add("implicit-euler-fd", "jacobian-throws");
        data.Add("implicit-euler-fd", "force-throws-in-solve");
        return data;
    }

    [Theory]
    [MemberData(nameof(Cases))]
    public void A_retry_after_a_failed_step_equals_the_step_from_a_restored_snapshot(string integrator, string failure)
    {
        var scene = new Scene(integrator);
        scene.Run(6);
        var good = SimulationSnapshot.Capture(scene.World, scene.Integrator);

        scene.Arm(failure);
        Assert.ThrowsAny<Exception>(() => scene.World.Step(scene.Integrator, Dt));
        scene.Disarm();
        AssertSame(good, SimulationSnapshot.Capture(scene.World, scene.Integrator), $"{integrator}, {failure}: after the failed step");

        scene.World.Step(scene.Integrator, Dt);
        var retried = SimulationSnapshot.Capture(scene.World, scene.Integrator);

        var restored = new Scene(integrator);
        good.RestoreTo(restored.World, restored.Integrator);
        restored.World.Step(restored.Integrator, Dt);
        AssertSame(SimulationSnapshot.Capture(restored.World, restored.Integrator), retried, $"{integrator}, {failure}: the retry");
    }

    [Theory]
    [InlineData("implicit-euler")]
    [InlineData("rk45")]
    public void A_step_changes_the_integrators_state_only_once_committed(string name)
    {
        var world = new ClothBuilder { Rows = 4, Columns = 4 }.Build().System;
        var integrator = (IStatefulIntegrator)IntegratorCatalog.Create(name);
        world.Step(integrator, Dt);
        world.Step(integrator, Dt);
        var before = State(integrator);

        var next = new double[world.Dimension];
        integrator.Step(world, world.Time, world.State, next, Dt);
        Assert.Equal(before, State(integrator));
        integrator.DiscardStep();
        integrator.CommitStep(); // nothing waits: a no-op
        Assert.Equal(before, State(integrator));

        integrator.Step(world, world.Time, world.State, next, Dt);
        integrator.CommitStep();
        Assert.NotEqual(before, State(integrator));
        var committed = State(integrator);
        integrator.CommitStep(); // committing twice commits once
        Assert.Equal(committed, State(integrator));

        // Reading a state forgets a step not yet committed.
        integrator.Step(world, world.Time, world.State, next, Dt);
        integrator.ReadState(before);
        integrator.CommitStep();
        Assert.Equal(before, State(integrator));
    }

    private static double[] State(IStatefulIntegrator integrator)
    {
        var state = new double[integrator.StateLength];
        integrator.WriteState(state);
        return state;
    }

    private static void AssertSame(SimulationSnapshot expected, SimulationSnapshot actual, string what)
    {
        Assert.True(expected.Time.Equals(actual.Time), $"{what}: time {actual.Time} vs {expected.Time}");
        Assert.True(StateMetrics.BitHash(expected.State) == StateMetrics.BitHash(actual.State), $"{what}: the state differs");
        Assert.True(StateMetrics.BitHash(expected.Masses) == StateMetrics.BitHash(actual.Masses), $"{what}: the masses differ");
        Assert.True(
            StateMetrics.BitHash(expected.IntegratorState) == StateMetrics.BitHash(actual.IntegratorState),
            $"{what}: the integrator's state differs ({expected.IntegratorState.Length} vs {actual.IntegratorState.Length} values)");
    }

    /// <summary>A small cloth with a user force and a user Jacobian that can be made to fail, and its integrator.</summary>
    private sealed class Scene
    {
        private readonly FaultyForce _force = new() { Particle = 7 };
        private readonly FaultyJacobianDrag _jacobian = new();
        private double _limit;

        public Scene(string integrator)
        {
            World = new ClothBuilder { Rows = 5, Columns = 5, Spacing = 0.2 }.WithSprings(40, 0.1).Build().System;
            World.AddForce(_force);
            World.AddForce(_jacobian);
            Integrator = integrator switch
            {
                "implicit-euler" => new ImplicitEuler(),
                "implicit-euler-fd" => new ImplicitEuler { UserForces = UserForceTreatment.FiniteDifference },
                _ => IntegratorCatalog.Create(integrator),
            };
        }

        public ParticleWorld World { get; }

        public IIntegrator Integrator { get; }

        /// <summary>The user force's evaluations in the last step of <see cref="Run"/>.</summary>
        public int EvaluationsPerStep { get; private set; }

        public void Run(int steps)
        {
            StateMetrics.Run(World, Integrator, Dt, steps - 1);
            var before = _force.TotalEvaluations;
            World.Step(Integrator, Dt);
            EvaluationsPerStep = (int)(_force.TotalEvaluations - before);
        }

        public void Arm(string failure)
        {
            _limit = World.DivergenceLimit;
            switch (failure)
            {
                case "diverges":
                    World.DivergenceLimit = 1e-9; // the step runs whole, then its result is refused
                    break;
                case "force-throws-first":
                    _force.Arm(Fault.Throw);
                    break;
                case "force-throws-later":
                    _force.Arm(Fault.Throw, afterEvaluations: Math.Min(2, EvaluationsPerStep - 1));
                    break;
                case "force-throws-in-solve":
                    _force.Arm(Fault.Throw, afterEvaluations: 6); // inside the finite-difference products of the solve
                    break;
                case "force-writes-nan":
                    _force.Arm(Fault.NaN, afterEvaluations: Math.Min(1, EvaluationsPerStep - 1));
                    break;
                case "jacobian-throws":
                    _jacobian.Arm(afterProducts: 3);
                    break;
                default:
                    throw new ArgumentOutOfRangeException(nameof(failure), failure, "unknown failure");
            }
        }

        public void Disarm()
        {
            World.DivergenceLimit = _limit;
            _force.Arm(Fault.None);
            _jacobian.Armed = false;
        }
    }
}
