using System;
using ParticlePhysics.Cloth;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Support;
using Xunit.Abstractions;

namespace ParticlePhysics.Tests.Implicit;

/// <summary>Implicit Euler against the course's closed form, exact backward Euler, its order, and the 60 Hz cloth.</summary>
[Collection(AllocationMeasurements.Name)]
public class ImplicitEulerTests
{
    private readonly ITestOutputHelper _output;

    public ImplicitEulerTests(ITestOutputHelper output) => _output = output;

    [Theory]
    [InlineData(0.01)]
    [InlineData(0.1)]
    [InlineData(1.0 / 60)]
    public void Free_fall_with_drag_reproduces_the_course_closed_form(double dt)
    {
        var scenario = new FreeFallScenario();
        var system = scenario.Build();
        var implicitEuler = new ImplicitEuler();
        var tau = scenario.Mass / scenario.Drag;
        double v = 0, y = scenario.Height;
        for (var step = 1; step <= 300; step++)
        {
            system.Step(implicitEuler, dt);
            v = (v - (scenario.Gravity * dt)) / (1 + (dt / tau)); // v(i+1) = (v(i) - g dt) / (1 + dt / tau), y up
            y += dt * v;                                          // x(i+1) = x(i) + dt v(i+1)
            Assert.Equal(v, system.GetVelocity(0).Y, 1e-12);
            Assert.Equal(y, system.GetPosition(0).Y, 1e-12 * Math.Max(1, Math.Abs(y)));
        }
    }

    [Fact]
    public void On_a_linear_system_it_equals_exact_backward_euler()
    {
        // Zero-rest-length springs, drag, dampers and gravity are linear: f = K x + D v + g. Backward Euler then
        // solves the linear system (M - h D - h^2 K) v1 = M v0 + h (K x0 + g) exactly; compare with a dense solve.
        var system = new ParticleWorld();
        var random = new Random(11);
        for (var i = 0; i < 6; i++)
        {
            system.AddParticle(
                new Vector3d(random.NextDouble(), random.NextDouble(), random.NextDouble()),
                new Vector3d(random.NextDouble() - 0.5, random.NextDouble() - 0.5, random.NextDouble() - 0.5),
                0.5 + random.NextDouble());
        }

        system.Pin(5);
        var springs = new ZeroLengthSprings(system);
        springs.Add(0, 1, 40);
        springs.Add(1, 2, 25);
        springs.Add(2, 3, 60);
        springs.Add(3, 4, 10);
        springs.Add(4, 5, 30);
        springs.Add(0, 3, 15);
        springs.AddAnchored(2, new Vector3d(0, 1, 0), 20);
        var dampers = new Dampers(system);
        dampers.Add(0, 4, 0.7);
        dampers.Add(1, 3, 0.3);
        system.AddForce(springs);
        system.AddForce(dampers);
        system.AddForce(new LinearDrag(0.2));
        system.AddForce(new Gravity());

        var implicitEuler = new ImplicitEuler { Tolerance = 1e-14, MaxIterations = 1000 };
        const double h = 0.05;
        for (var step = 0; step < 40; step++)
        {
            var expected = DenseBackwardEuler(system, h);
            system.Step(implicitEuler, h);
            Assert.True(implicitEuler.LastConverged);
            var error = StateMetrics.MaxAbsError(system.State, expected);
            Assert.True(error < 1e-12, $"step {step}: {error}");
        }

        Assert.Equal(Vector3d.Zero, system.GetVelocity(5));
    }

    [Theory]
    [InlineData("mass-spring-damper")]
    [InlineData("two-mass-chain")]
    [InlineData("time-dependent-drive")]
    public void Observed_order_is_one(string problem)
    {
        var integrator = () => new ImplicitEuler { Tolerance = 1e-13, MaxIterations = 100 };
        double Error(double h)
        {
            switch (problem)
            {
                case "mass-spring-damper":
                    var msd = new MassSpringDamperScenario { Damping = 0.3, Y0 = 1, V0 = 0.5 };
                    return ErrorAt(msd.Build(), msd, integrator(), h, 4);
                case "two-mass-chain":
                    var chain = new TwoMassChainScenario();
                    return ErrorAt(chain.Build(), chain, integrator(), h, 2);
                default:
                    var drive = new HarmonicDrive(2.0, 3.0);
                    var system = new ParticleWorld();
                    system.AddParticle(new Vector3d(0.5, 0, 0), new Vector3d(-1, 0, 0), 2.0);
                    system.AddForce(drive);
                    var steps = (int)Math.Round(2.0 / h);
                    StateMetrics.Run(system, integrator(), h, steps);
                    var expected = new double[6];
                    drive.ExactState(0.5, -1, steps * h, expected);
                    return StateMetrics.MaxAbsError(system.State, expected);
            }
        }

        var orders = StateMetrics.ObservedOrders(Error, 0.01, 4);
        _output.WriteLine($"implicit-euler on {problem}: {string.Join(", ", Array.ConvertAll(orders, o => o.ToString("F3")))}");
        Assert.All(orders, order => Assert.InRange(order, 0.9, 1.1));
    }

    [Fact]
    public void The_scalar_ode_is_solved_by_newton_and_converges_at_order_one()
    {
        var ode = new GaussianDecayOde();
        double Error(double h)
        {
            var simulation = new OdeSimulation(ode, new[] { 1.0 });
            var implicitEuler = new ImplicitEuler();
            var steps = (int)Math.Round(2.0 / h);
            for (var s = 0; s < steps; s++)
            {
                simulation.Step(implicitEuler, h);
                Assert.True(implicitEuler.LastConverged);
            }

            return Math.Abs(simulation.State[0] - Math.Exp(-Math.Pow(steps * h, 2)));
        }

        // One step by hand: y1 = y0 + h (-2 (t + h) y1)  =>  y1 = y0 / (1 + 2 h (t + h)).
        var one = new OdeSimulation(ode, new[] { 1.0 });
        one.Step(new ImplicitEuler(), 0.1);
        Assert.Equal(1.0 / 1.02, one.State[0], 15);

        var orders = StateMetrics.ObservedOrders(Error, 0.01, 4);
        Assert.All(orders, order => Assert.InRange(order, 0.9, 1.1));
    }

    [Fact]
    public void The_default_cloth_at_60_hz_stays_finite_hangs_and_never_gains_energy()
    {
        var system = new ClothScenario().Build();
        var implicitEuler = new ImplicitEuler();
        var energy = TotalEnergy(system);
        var worstIterations = 0;
        for (var step = 0; step < 600; step++)
        {
            system.Step(implicitEuler, 1.0 / 60);
            Assert.True(implicitEuler.LastConverged, $"step {step}: residual {implicitEuler.LastResidual}");
            worstIterations = Math.Max(worstIterations, implicitEuler.LastIterations);
            var next = TotalEnergy(system);
            Assert.True(next <= energy, $"energy rose at step {step}: {energy} -> {next}");
            energy = next;
        }

        var lowest = double.PositiveInfinity;
        for (var i = 0; i < system.Count; i++)
        {
            lowest = Math.Min(lowest, system.GetPosition(i).Y);
        }

        _output.WriteLine($"lowest point {lowest} m, worst CG iterations {worstIterations}, kinetic energy {system.KineticEnergy()}");
        Assert.InRange(lowest, -1.2, -0.95);        // a 1 m cloth held by two corners hangs about 1 m below them
        Assert.True(system.KineticEnergy() < 1e-3); // and has come to rest
        Assert.Equal(Vector3d.Zero, system.GetPosition(0));
        Assert.Equal(new Vector3d(1, 0, 0), system.GetPosition(10));
    }

    [Fact]
    public void Rk4_at_the_same_dt_diverges_and_is_reported()
    {
        var system = new ClothScenario().Build();
        Assert.Throws<SimulationDivergedException>(() => StateMetrics.Run(system, new RungeKutta4(), 1.0 / 60, 600));
    }

    [Fact]
    public void At_its_iteration_cap_the_step_ends_with_the_best_solution_and_says_so()
    {
        var system = new ClothScenario().Build();
        StateMetrics.Run(system, new ImplicitEuler(), 1.0 / 60, 10); // from rest the first solve is diagonal: let it swing
        var capped = new ImplicitEuler { MaxIterations = 3, Tolerance = 1e-12 };
        system.Step(capped, 1.0 / 60);
        Assert.False(capped.LastConverged);
        Assert.Equal(3, capped.LastIterations);
        Assert.InRange(capped.LastResidual, 1e-12, 1.0);
        Assert.Equal(11.0 / 60, system.Time, 15);
        Assert.All(system.State.ToArray(), value => Assert.True(double.IsFinite(value)));
    }

    [Fact]
    public void At_its_iteration_cap_it_can_throw_instead_and_leave_the_system_as_it_was()
    {
        var system = new ClothScenario().Build();
        StateMetrics.Run(system, new ImplicitEuler(), 1.0 / 60, 10);
        var before = StateMetrics.BitHash(system.State);
        var strict = new ImplicitEuler { MaxIterations = 3, Tolerance = 1e-12, ThrowIfNotConverged = true };
        var ex = Assert.Throws<SolverNotConvergedException>(() => system.Step(strict, 1.0 / 60));
        Assert.Equal(3, ex.Iterations);
        Assert.Contains("did not converge", ex.Message, StringComparison.Ordinal);
        Assert.Equal(before, StateMetrics.BitHash(system.State));
        Assert.Equal(10.0 / 60, system.Time, 15);
    }

    [Fact]
    public void Pinned_particles_stay_exactly_in_place()
    {
        var system = new ClothScenario { Pinning = ClothPinning.Edge }.Build();
        var implicitEuler = new ImplicitEuler();
        StateMetrics.Run(system, implicitEuler, 1.0 / 60, 60);
        for (var col = 0; col < 11; col++)
        {
            Assert.Equal(new Vector3d(col * 0.1, 0, 0), system.GetPosition(col));
            Assert.Equal(Vector3d.Zero, system.GetVelocity(col));
        }
    }

    [Fact]
    public void Invalid_settings_are_refused()
    {
        var implicitEuler = new ImplicitEuler();
        Assert.Throws<ArgumentOutOfRangeException>("Tolerance", () => implicitEuler.Tolerance = 0);
        Assert.Throws<ArgumentOutOfRangeException>("Tolerance", () => implicitEuler.Tolerance = double.NaN);
        Assert.Throws<ArgumentOutOfRangeException>("MaxIterations", () => implicitEuler.MaxIterations = 0);
        Assert.Equal(1e-6, implicitEuler.Tolerance);
    }

    [Fact]
    public void Stepping_allocates_nothing_after_the_first_step()
    {
        var system = new ClothScenario().Build();
        var implicitEuler = new ImplicitEuler { UserForces = UserForceTreatment.FiniteDifference };
        system.AddForce(new Engine.ReadmeExamplesTests.Wind { AirVelocity = new Vector3d(1, 0, 0.5) });
        StateMetrics.Run(system, implicitEuler, 1.0 / 60, 2);
        Assert.Equal(0, ThreadAllocations.Measure(() => StateMetrics.Run(system, implicitEuler, 1.0 / 60, 30)));
    }

    internal static double TotalEnergy(ParticleWorld system) => system.KineticEnergy() + system.PotentialEnergy();

    private static double ErrorAt(ParticleWorld system, IExactSolution exact, IIntegrator integrator, double h, double duration)
    {
        var steps = (int)Math.Round(duration / h);
        StateMetrics.Run(system, integrator, h, steps);
        var expected = new double[system.Dimension];
        exact.ExactState(steps * h, expected);
        return StateMetrics.MaxAbsError(system.State, expected);
    }

    /// <summary>
    /// Backward Euler for a linear force f = f0 + K dx + D dv by a dense solve (MathNet): M v1 = M v0 + h f(x1, v1)
    /// with x1 = x0 + h v1, solved for dv = v1 - v0. K and D are read off the forces by unit differences (exact for
    /// a linear force up to rounding). Pinned particles are held.
    /// </summary>
    private static double[] DenseBackwardEuler(ParticleWorld system, double h)
    {
        var n = system.CoordinateCount;
        var x0 = system.Positions.ToArray();
        var v0 = system.Velocities.ToArray();
        double[] Force(double[] x, double[] v) => system.AccumulateForces(0, x, v).ToArray();
        var f0 = Force(x0, v0);
        var a = MathNet.Numerics.LinearAlgebra.Matrix<double>.Build.Dense(n, n);
        var rhs = MathNet.Numerics.LinearAlgebra.Vector<double>.Build.Dense(n);
        var k = new double[n, n];
        for (var col = 0; col < n; col++)
        {
            var xs = (double[])x0.Clone();
            xs[col] += 1.0;
            var vs = (double[])v0.Clone();
            vs[col] += 1.0;
            var fx = Force(xs, v0);
            var fv = Force(x0, vs);
            for (var row = 0; row < n; row++)
            {
                k[row, col] = fx[row] - f0[row];
                a[row, col] = -(h * (fv[row] - f0[row])) - (h * h * k[row, col]);
            }
        }

        for (var row = 0; row < n; row++)
        {
            var m = system.Masses[row / 3];
            a[row, row] += m;
            // In terms of dv = v1 - v0 the same system reads (M - h D - h^2 K) dv = h (f0 + h K v0).
            var kv = 0.0;
            for (var col = 0; col < n; col++)
            {
                kv += k[row, col] * v0[col];
            }

            rhs[row] = h * (f0[row] + (h * kv));
        }

        for (var i = 0; i < system.Count; i++)
        {
            if (!system.IsPinned(i))
            {
                continue;
            }

            for (var c = 0; c < 3; c++)
            {
                var row = (3 * i) + c;
                for (var col = 0; col < n; col++)
                {
                    a[row, col] = row == col ? 1 : 0;
                    a[col, row] = row == col ? 1 : 0;
                }

                rhs[row] = 0;
            }
        }

        var dv = a.Solve(rhs);
        var next = new double[2 * n];
        for (var row = 0; row < n; row++)
        {
            next[n + row] = v0[row] + dv[row];
            next[row] = x0[row] + (h * next[n + row]);
        }

        return next;
    }
}
