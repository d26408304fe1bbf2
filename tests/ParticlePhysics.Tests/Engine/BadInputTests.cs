using System;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Engine;

/// <summary>
/// Every public entry point rejects what makes no sense with an ArgumentException that names the parameter and the
/// value, and leaves the system exactly as it was.
/// </summary>
public class BadInputTests
{
    // The last four (issue 10, item 7): positive and finite, but 1 / m overflows, so the first step failed with a
    // misleading "retry with a smaller time step".
    public static TheoryData<double> BadMasses() => new()
    {
        0.0, -1.0, double.NaN, double.PositiveInfinity, double.NegativeInfinity, 5e-324, 1e-320, 4.9e-309, 5.562684646268003e-309,
    };

    public static TheoryData<double> NonFinite() => new() { double.NaN, double.PositiveInfinity, double.NegativeInfinity };

    public static TheoryData<double> BadTimeSteps() => new() { 0.0, -0.01, double.NaN, double.PositiveInfinity };

    public static TheoryData<double> Negative() => new() { -1.0, -1e-300, double.NaN, double.NegativeInfinity };

    [Theory]
    [MemberData(nameof(BadMasses))]
    public void A_mass_that_is_not_positive_and_finite_is_refused(double mass)
    {
        var system = TwoParticles(out _);
        AssertRejected(system, "mass", mass, () => system.AddParticle(Vector3d.Zero, mass));
        AssertRejected(system, "mass", mass, () => system.SetMass(0, mass));
    }

    [Fact]
    public void The_smallest_mass_whose_inverse_is_finite_is_accepted_and_steps()
    {
        var system = TwoParticles(out _);
        system.SetMass(1, 5.56268464626801e-309);
        Assert.True(double.IsFinite(system.InverseMasses[1]));
        system.AddParticle(Vector3d.Zero, 5.56268464626801e-309);
    }

    [Theory]
    [MemberData(nameof(NonFinite))]
    public void A_position_or_velocity_that_is_not_finite_is_refused(double bad)
    {
        var system = TwoParticles(out _);
        AssertRejected(system, "position", null, () => system.AddParticle(new Vector3d(0, bad, 0), 1));
        AssertRejected(system, "velocity", null, () => system.AddParticle(Vector3d.Zero, new Vector3d(bad, 0, 0), 1));
        AssertRejected(system, "position", null, () => system.SetPosition(1, new Vector3d(0, 0, bad)));
        AssertRejected(system, "velocity", null, () => system.SetVelocity(1, new Vector3d(0, bad, 0)));
        var state = system.State.ToArray();
        state[7] = bad;
        AssertRejected(system, "state", null, () => system.SetState(state));
    }

    [Fact]
    public void A_spring_or_damper_joining_a_particle_to_itself_is_refused()
    {
        var system = TwoParticles(out var springs);
        AssertRejected(system, "second", null, () => springs.Add(1, 1, 10, 1));
        AssertRejected(system, "second", null, () => new ZeroLengthSprings(system).Add(0, 0, 1));
        AssertRejected(system, "second", null, () => new Dampers(system).Add(1, 1, 1));
        Assert.Equal(1, springs.Count);
    }

    [Theory]
    [InlineData(-1)]
    [InlineData(2)]
    [InlineData(int.MaxValue)]
    public void A_particle_that_does_not_exist_is_refused(int index)
    {
        var system = TwoParticles(out var springs);
        AssertRejected(system, "second", index, () => springs.Add(0, index, 1, 1));
        AssertRejected(system, "first", index, () => springs.Add(index, 0, 1, 1));
        AssertRejected(system, "particle", index, () => springs.AddAnchored(index, Vector3d.Zero, 1, 1));
        AssertRejected(system, "particles", index, () => new LinearDrag(0.1, system, new[] { 0, index }));
        AssertRejected(system, "index", index, () => system.SetPosition(index, Vector3d.Zero));
        AssertRejected(system, "index", index, () => system.Pin(index));
        Assert.Equal(1, springs.Count);
    }

    [Theory]
    [MemberData(nameof(Negative))]
    public void A_negative_stiffness_damping_rest_length_or_drag_is_refused(double bad)
    {
        var system = TwoParticles(out var springs);
        AssertRejected(system, "stiffness", bad, () => springs.Add(0, 1, bad, 1));
        AssertRejected(system, "restLength", bad, () => springs.Add(0, 1, 1, bad));
        AssertRejected(system, "damping", bad, () => springs.Add(0, 1, 1, 1, bad));
        AssertRejected(system, "stiffness", bad, () => springs.SetStiffness(0, bad));
        AssertRejected(system, "stiffness", bad, () => new ZeroLengthSprings(system).AddAnchored(0, Vector3d.Zero, bad));
        AssertRejected(system, "damping", bad, () => new Dampers(system).Add(0, 1, bad));
        AssertRejected(system, "coefficient", bad, () => new LinearDrag(bad));
        var drag = new LinearDrag(0.5);
        Assert.Throws<ArgumentOutOfRangeException>("Coefficient", () => drag.Coefficient = bad);
        Assert.Equal(0.5, drag.Coefficient);
    }

    [Theory]
    [MemberData(nameof(BadTimeSteps))]
    public void A_time_step_that_is_not_a_positive_finite_number_is_refused(double dt)
    {
        foreach (var name in IntegratorCatalog.Names)
        {
            var system = TwoParticles(out _);
            AssertRejected(system, "dt", dt, () => system.Step(IntegratorCatalog.Create(name), dt));
        }

        var simulation = new OdeSimulation(new Scenarios.GaussianDecayOde(), new[] { 1.0 });
        var ex = Assert.Throws<ArgumentOutOfRangeException>("dt", () => simulation.Step(new RungeKutta4(), dt));
        Assert.Contains(Guard.Format(dt), ex.Message, StringComparison.Ordinal);
        Assert.Equal(0, simulation.Time);
        Assert.Equal(1.0, simulation.State[0]);
    }

    [Fact]
    public void A_step_that_would_end_at_an_infinite_time_is_refused()
    {
        // Issue 10, item 9: from double.MaxValue, dt = 1e300 made Time +infinity, and that state's snapshot could be
        // written but not read back.
        foreach (var name in IntegratorCatalog.Names)
        {
            var system = TwoParticles(out _);
            system.Time = double.MaxValue;
            AssertRejected(system, "dt", 1e300, () => system.Step(IntegratorCatalog.Create(name), 1e300));
            Assert.Equal(double.MaxValue, system.Time);
        }

        // Found by the API fuzzer: from t = double.MaxValue a dt of 0.005 vanished (t + dt == t), so the step moved
        // nothing, reported success, and rk45 kept a step size computed from a step that never ran.
        foreach (var (time, dt) in new[] { (double.MaxValue, 0.005), (1e20, 1e-3), (1.0, 1e-17) })
        {
            var system = TwoParticles(out _);
            system.Time = time;
            AssertRejected(system, "dt", dt, () => system.Step(new DormandPrince45(), dt));
        }

        var simulation = new OdeSimulation(new Scenarios.GaussianDecayOde(), new[] { 1.0 }, initialTime: double.MaxValue);
        var ex = Assert.Throws<ArgumentOutOfRangeException>("dt", () => simulation.Step(new ExplicitEuler(), 1e300));
        Assert.Contains("end time must be finite", ex.Message, StringComparison.Ordinal);
        Assert.Equal(double.MaxValue, simulation.Time);
    }

    [Theory]
    [InlineData(-1)]
    [InlineData(ParticleWorld.MaxParticles + 1)]
    [InlineData(357_913_942)] // the smallest capacity whose 6 values per particle overflow an int
    [InlineData(int.MaxValue)]
    public void A_capacity_outside_0_to_the_world_limit_is_refused_with_its_value(int capacity)
    {
        // Issue 10, item 10: capacities from 357,913,942 up threw OverflowException.
        var ex = Assert.Throws<ArgumentOutOfRangeException>("capacity", () => new ParticleWorld(capacity));
        Assert.Contains(capacity.ToString(System.Globalization.CultureInfo.InvariantCulture), ex.Message, StringComparison.Ordinal);
        Assert.Contains("4194304", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void A_force_generator_built_for_another_system_or_added_twice_is_refused()
    {
        var system = TwoParticles(out var springs);
        var other = TwoParticles(out var foreignSprings);
        AssertRejected(system, "generator", null, () => system.AddForce(foreignSprings));
        AssertRejected(system, "generator", null, () => system.AddForce(springs));
        Assert.Throws<ArgumentNullException>("generator", () => system.AddForce(null!));
        Assert.Equal(2, other.Forces.Count);
    }

    [Fact]
    public void A_kinematic_drive_needs_a_pinned_particle_a_finite_target_and_a_positive_duration()
    {
        var system = TwoParticles(out _);
        Assert.Throws<InvalidOperationException>(() => system.MoveKinematic(0, new Vector3d(1, 0, 0), 0.1));
        system.Pin(0);
        AssertRejected(system, "duration", 0.0, () => system.MoveKinematic(0, Vector3d.Zero, 0));
        AssertRejected(system, "target", null, () => system.MoveKinematic(0, new Vector3d(double.NaN, 0, 0), 0.1));
        AssertRejected(system, "duration", 1e-300, () => system.MoveKinematic(0, new Vector3d(1e300, 0, 0), 1e-300));
        AssertRejected(system, "velocity", null, () => system.Pin(0, new Vector3d(0, double.PositiveInfinity, 0)));
        AssertRejected(system, "index", 2, () => system.MoveKinematic(2, Vector3d.Zero, 1));
    }

    [Fact]
    public void Semi_implicit_euler_and_verlet_refuse_a_plain_first_order_system()
    {
        foreach (var name in new[] { "semi-implicit-euler", "velocity-verlet" })
        {
            var simulation = new OdeSimulation(new Scenarios.GaussianDecayOde(), new[] { 1.0 });
            var ex = Assert.Throws<ArgumentException>("system", () => simulation.Step(IntegratorCatalog.Create(name), 0.1));
            Assert.Contains("position/velocity", ex.Message, StringComparison.Ordinal);
            Assert.Equal(1.0, simulation.State[0]);
        }
    }

    [Fact]
    public void An_unknown_integrator_name_lists_the_known_ones()
    {
        var ex = Assert.Throws<ArgumentException>("name", () => IntegratorCatalog.Create("rk5"));
        Assert.Contains("rk5", ex.Message, StringComparison.Ordinal);
        Assert.Contains("velocity-verlet", ex.Message, StringComparison.Ordinal);
    }

    private static ParticleWorld TwoParticles(out SpringNetwork springs)
    {
        var system = new ParticleWorld();
        system.AddParticle(new Vector3d(0, 0, 0), 1.0);
        system.AddParticle(new Vector3d(0, -1.5, 0), new Vector3d(0.1, 0, 0), 2.0);
        springs = new SpringNetwork(system);
        springs.Add(0, 1, 10, 1, 0.1);
        system.AddForce(springs);
        system.AddForce(new Gravity());
        system.Step(new RungeKutta4(), 0.01);
        return system;
    }

    private static void AssertRejected(ParticleWorld system, string parameter, object? value, Action action)
    {
        var before = Snapshot(system);
        var ex = Assert.ThrowsAny<ArgumentException>(action);
        Assert.Equal(parameter, ex.ParamName);
        if (value is double d)
        {
            Assert.Contains(Guard.Format(d), ex.Message, StringComparison.Ordinal);
        }
        else if (value is int i)
        {
            Assert.Contains(i.ToString(System.Globalization.CultureInfo.InvariantCulture), ex.Message, StringComparison.Ordinal);
        }

        Assert.Equal(before, Snapshot(system));
    }

    private static string Snapshot(ParticleWorld system)
    {
        var pins = new double[system.Count];
        for (var i = 0; i < system.Count; i++)
        {
            pins[i] = system.IsPinned(i) ? 1 : 0;
        }

        return string.Join(
            "|",
            system.Count,
            system.Forces.Count,
            StateMetrics.BitHash(new[] { system.Time }),
            StateMetrics.BitHash(system.State),
            StateMetrics.BitHash(system.Masses),
            StateMetrics.BitHash(system.InverseMasses),
            StateMetrics.BitHash(pins));
    }
}
