using System;
using System.Numerics;
using ParticlePhysics.Cloth;
using ParticlePhysics.Driver;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Driver;

/// <summary>The fixed-timestep driver: whole steps, carried remainder, capped frames, interpolation, determinism.</summary>
[Collection(AllocationMeasurements.Name)]
public class FixedTimestepDriverTests
{
    // 1/64 s: a power of two, so that the frame times below add up exactly and every sequence gives 40 steps.
    private const double Dt = 1.0 / 64;

    public static TheoryData<double> BadFrameTimes() =>
        new() { -1e-9, -0.016, double.NaN, double.PositiveInfinity, double.NegativeInfinity };

    [Fact]
    public void Different_frame_time_sequences_with_the_same_steps_give_bit_identical_states()
    {
        var sequences = new[]
        {
            Repeat(Dt, 40),
            Repeat(Dt / 2, 80),
            Repeat(Dt * 5 / 4, 32),
            Concat(Repeat(3 * Dt / 8, 3), Repeat(Dt * 7 / 8, 1), Repeat(Dt * 3, 12), Repeat(Dt / 4, 8)),
            new[] { 40 * Dt },
        };
        string? expected = null;
        foreach (var frames in sequences)
        {
            var cloth = SmallCloth();
            var driver = new FixedTimestepDriver(cloth.System, new RungeKutta4(), Dt, subSteps: 3, maxStepsPerFrame: 64);
            var steps = 0;
            foreach (var frame in frames)
            {
                steps += driver.Advance(frame);
            }

            Assert.Equal(40, steps);
            Assert.Equal(40, driver.StepCount);
            Assert.Equal(0.0, driver.Accumulator);
            var hash = StateMetrics.BitHash(cloth.System.State);
            expected ??= hash;
            Assert.Equal(expected, hash);
        }

        // And the same as stepping by hand: 40 fixed steps of three sub-steps each.
        var reference = SmallCloth().System;
        StateMetrics.Run(reference, new RungeKutta4(), Dt / 3, 120);
        Assert.Equal(expected, StateMetrics.BitHash(reference.State));
    }

    [Fact]
    public void The_remainder_is_carried_to_the_next_frame()
    {
        var driver = new FixedTimestepDriver(FallingParticle(), new SemiImplicitEuler(), Dt);
        Assert.Equal(1, driver.Advance(1.5 * Dt));
        Assert.Equal(0.5 * Dt, driver.Accumulator);
        Assert.Equal(0.5, driver.InterpolationFactor);
        Assert.Equal(0, driver.Advance(0.25 * Dt));
        Assert.Equal(0.75, driver.InterpolationFactor);
        Assert.Equal(1, driver.Advance(0.25 * Dt));
        Assert.Equal(0.0, driver.Accumulator);
        Assert.Equal(2, driver.StepCount);
        Assert.Equal(2 * Dt, driver.System.Time);
    }

    [Fact]
    public void A_long_frame_runs_at_most_the_cap_and_reports_the_time_it_dropped()
    {
        var driver = new FixedTimestepDriver(FallingParticle(), new SemiImplicitEuler(), Dt, maxStepsPerFrame: 4);
        Assert.Equal(4, driver.Advance(10.25 * Dt));
        Assert.Equal(6 * Dt, driver.LastDroppedTime);
        Assert.Equal(0.25 * Dt, driver.Accumulator);
        Assert.Equal(4 * Dt, driver.System.Time);
        Assert.Equal(2, driver.Advance(1.75 * Dt));
        Assert.Equal(0.0, driver.LastDroppedTime);
        Assert.Equal(6 * Dt, driver.TotalDroppedTime);
    }

    [Fact]
    public void A_pause_of_any_length_is_dropped_whole_and_leaves_a_fraction_of_a_step()
    {
        var driver = new FixedTimestepDriver(FallingParticle(), new SemiImplicitEuler(), 0.01, maxStepsPerFrame: 2);
        Assert.Equal(2, driver.Advance(1e9));
        Assert.InRange(driver.Accumulator, 0.0, 0.01);
        Assert.True(driver.Accumulator < 0.01);
        Assert.Equal(1e9 - 0.02, driver.LastDroppedTime + driver.Accumulator, 3);
        Assert.Equal(1, driver.Advance(0.01));
    }

    [Fact]
    public void A_frame_that_diverges_leaves_everything_as_it_was_before_the_call()
    {
        // SCENARIOS.md: explicit methods diverge on the default cloth at one 60 Hz frame per step. Issue 10, item 5:
        // before, the world kept the steps that had passed and the accumulator the time of those that had not.
        var system = new ParticlePhysics.Scenarios.ClothScenario().Build();
        var driver = new FixedTimestepDriver(system, new ExplicitEuler(), 1.0 / 64, maxStepsPerFrame: 1000);
        driver.Advance(0.5 / 64);
        var before = Observe(driver);

        var e = Assert.Throws<SimulationDivergedException>(() => driver.Advance(500.0 / 64));
        Assert.Equal(0.0, e.LastFiniteTime);
        Assert.Contains("last good state, t=0;", e.Message, StringComparison.Ordinal);
        Assert.True(e.Time > 1.0 / 64);
        Assert.Equal(before, Observe(driver));
    }

    [Fact]
    public void A_sub_step_that_fails_in_the_middle_of_a_fixed_step_takes_the_whole_frame_back()
    {
        // The fuzzer's case: sub-step 3 of 4 failed, the world kept 2 sub-steps, the accumulator still held the frame
        // and the interpolation's start was overwritten; the next Advance(0) left the time 2.5 fixed steps on, off the grid.
        var cloth = SmallCloth();
        var force = new FaultyForce { Particle = 9 };
        cloth.System.AddForce(force);
        var implicitEuler = new ImplicitEuler();
        var driver = new FixedTimestepDriver(cloth.System, implicitEuler, Dt, subSteps: 4);
        driver.Advance(2.5 * Dt);
        var before = Observe(driver);
        var warmStart = IntegratorState(implicitEuler);

        force.Arm(Fault.Throw, afterEvaluations: 2); // implicit Euler evaluates once per sub-step: the third fails
        Assert.Throws<InvalidOperationException>(() => driver.Advance(Dt));
        Assert.Equal(before, Observe(driver));
        Assert.Equal(warmStart, IntegratorState(implicitEuler));
        Assert.Equal(0, driver.Advance(0));
        Assert.Equal(2 * Dt, cloth.System.Time);

        // Retried, the frame gives what a driver that never failed gives.
        force.Arm(Fault.None);
        driver.Advance(Dt);
        var reference = SmallCloth();
        reference.System.AddForce(new FaultyForce { Particle = 9 });
        var referenceDriver = new FixedTimestepDriver(reference.System, new ImplicitEuler(), Dt, subSteps: 4);
        referenceDriver.Advance(2.5 * Dt);
        referenceDriver.Advance(Dt);
        Assert.Equal(Observe(referenceDriver), Observe(driver));
    }

    [Fact]
    public void A_frame_of_one_step_needs_no_copy_and_is_all_or_nothing_too()
    {
        var cloth = SmallCloth();
        var force = new FaultyForce { Particle = 3 };
        cloth.System.AddForce(force);
        var driver = new FixedTimestepDriver(cloth.System, new DormandPrince45(), Dt);
        driver.Advance(1.5 * Dt);
        var before = Observe(driver);
        force.Arm(Fault.NaN);
        Assert.Throws<SimulationDivergedException>(() => driver.Advance(0.7 * Dt));
        Assert.Equal(before, Observe(driver));
    }

    /// <summary>Everything a failed Advance must leave alone, as one string.</summary>
    private static string Observe(FixedTimestepDriver driver)
    {
        var vertices = new Vector3[driver.System.Count];
        driver.InterpolatePositions(vertices);
        var rendered = new double[3 * vertices.Length];
        for (var i = 0; i < vertices.Length; i++)
        {
            rendered[3 * i] = vertices[i].X;
            rendered[(3 * i) + 1] = vertices[i].Y;
            rendered[(3 * i) + 2] = vertices[i].Z;
        }

        return string.Join(
            "|",
            StateMetrics.BitHash(driver.System.State),
            StateMetrics.BitHash(new[] { driver.System.Time, driver.Accumulator, driver.LastDroppedTime, driver.TotalDroppedTime }),
            driver.StepCount,
            StateMetrics.BitHash(rendered),
            driver.Integrator is IStatefulIntegrator stateful ? StateMetrics.BitHash(IntegratorState(stateful)) : "-");
    }

    private static double[] IntegratorState(IStatefulIntegrator integrator)
    {
        var state = new double[integrator.StateLength];
        integrator.WriteState(state);
        return state;
    }

    [Fact]
    public void Interpolated_positions_blend_the_last_two_states()
    {
        var system = FallingParticle();
        var driver = new FixedTimestepDriver(system, new SemiImplicitEuler(), Dt);
        driver.Advance(Dt);
        var before = system.GetPosition(0);
        driver.Advance(1.25 * Dt);
        var after = system.GetPosition(0);
        Assert.Equal(0.25, driver.InterpolationFactor);
        Span<Vector3> rendered = stackalloc Vector3[1];
        driver.InterpolatePositions(rendered);
        Assert.Equal((float)((0.75 * before.Y) + (0.25 * after.Y)), rendered[0].Y);
        Assert.Equal(1f, rendered[0].X);

        driver.ResetInterpolation();
        driver.InterpolatePositions(rendered);
        Assert.Equal((float)after.Y, rendered[0].Y);
    }

    [Fact]
    public void Interpolation_can_write_one_body_of_a_shared_system()
    {
        var system = FallingParticle();
        var cloth = new ClothBuilder { Rows = 2, Columns = 3 }.AddTo(system);
        var driver = new FixedTimestepDriver(system, new RungeKutta4(), Dt);
        driver.Advance(2.5 * Dt);
        var vertices = new Vector3[cloth.ParticleCount];
        driver.InterpolatePositions(cloth.FirstParticle, cloth.ParticleCount, vertices);
        Assert.Equal(0.1f, vertices[4].X, 3); // particle (1, 1) of the cloth, not the falling particle at x = 1
        Assert.Throws<ArgumentOutOfRangeException>(() => driver.InterpolatePositions(2, cloth.ParticleCount, vertices));
        Assert.Throws<ArgumentException>(() => driver.InterpolatePositions(1, cloth.ParticleCount, new Vector3[2]));
    }

    [Fact]
    public void Sub_steps_divide_the_fixed_step()
    {
        var a = FallingParticle();
        new FixedTimestepDriver(a, new VelocityVerlet(), Dt, subSteps: 4).Advance(3 * Dt);
        var b = FallingParticle();
        StateMetrics.Run(b, new VelocityVerlet(), Dt / 4, 12);
        Assert.Equal(StateMetrics.BitHash(b.State), StateMetrics.BitHash(a.State));
    }

    [Theory]
    [MemberData(nameof(BadFrameTimes))]
    public void A_frame_time_that_is_negative_or_not_finite_is_refused(double frameTime)
    {
        var driver = new FixedTimestepDriver(FallingParticle(), new SemiImplicitEuler(), Dt);
        driver.Advance(0.5 * Dt);
        var e = Assert.Throws<ArgumentOutOfRangeException>(() => driver.Advance(frameTime));
        Assert.Equal("frameTime", e.ParamName);
        Assert.Contains(Guard.Format(frameTime), e.Message, StringComparison.Ordinal);
        Assert.Equal(0.5 * Dt, driver.Accumulator);
    }

    [Fact]
    public void Bad_settings_are_refused_with_their_names()
    {
        var system = FallingParticle();
        var rk4 = new RungeKutta4();
        Assert.Equal("fixedTimeStep", Assert.Throws<ArgumentOutOfRangeException>(() => new FixedTimestepDriver(system, rk4, 0)).ParamName);
        Assert.Equal("fixedTimeStep", Assert.Throws<ArgumentOutOfRangeException>(() => new FixedTimestepDriver(system, rk4, double.NaN)).ParamName);
        Assert.Equal("subSteps", Assert.Throws<ArgumentOutOfRangeException>(() => new FixedTimestepDriver(system, rk4, Dt, 0)).ParamName);
        Assert.Equal("maxStepsPerFrame", Assert.Throws<ArgumentOutOfRangeException>(() => new FixedTimestepDriver(system, rk4, Dt, 1, 0)).ParamName);
        Assert.Equal("integrator", Assert.Throws<ArgumentNullException>(() => new FixedTimestepDriver(system, null!, Dt)).ParamName);
    }

    [Fact]
    public void A_system_that_grew_after_the_driver_was_made_is_reported()
    {
        var system = FallingParticle();
        var driver = new FixedTimestepDriver(system, new RungeKutta4(), Dt);
        system.AddParticle(Vector3d.Zero, 1);
        Assert.Throws<InvalidOperationException>(() => driver.Advance(Dt));
    }

    [Fact]
    public void Advancing_and_interpolating_allocate_nothing()
    {
        var cloth = SmallCloth();
        var driver = new FixedTimestepDriver(cloth.System, new RungeKutta4(), Dt, subSteps: 2, maxStepsPerFrame: 3);
        var vertices = new Vector3[cloth.ParticleCount];
        var normals = new Vector3[cloth.ParticleCount];
        driver.Advance(Dt);
        Assert.Equal(0, ThreadAllocations.Measure(() =>
        {
            for (var frame = 0; frame < 50; frame++)
            {
                driver.Advance(frame % 7 == 0 ? 5.3 * Dt : 0.7 * Dt);
                driver.InterpolatePositions(cloth.FirstParticle, cloth.ParticleCount, vertices);
                cloth.Mesh.ComputeNormals(vertices, normals);
            }
        }));
    }

    internal static ParticleCloth SmallCloth() =>
        new ClothBuilder { Rows = 5, Columns = 6, Spacing = 0.1 }.Build();

    private static ParticleWorld FallingParticle()
    {
        var system = new ParticleWorld();
        system.AddParticle(new Vector3d(1, 10, 0), 1);
        system.AddForce(new Gravity());
        return system;
    }

    private static double[] Repeat(double value, int count)
    {
        var values = new double[count];
        Array.Fill(values, value);
        return values;
    }

    private static double[] Concat(params double[][] parts)
    {
        var all = new System.Collections.Generic.List<double>();
        foreach (var part in parts)
        {
            all.AddRange(part);
        }

        return all.ToArray();
    }
}
