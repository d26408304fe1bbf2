using System;
using MathNet.Numerics.LinearAlgebra;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Tests.Physics;

/// <summary>
/// The scenarios' exact solutions are themselves checked, independently of any integrator: they meet their initial
/// conditions and satisfy their differential equations (by central differences), and the chain's matches an eigen
/// decomposition computed by MathNet.Numerics.
/// </summary>
public class ExactSolutionTests
{
    private const double H = 1e-4;

    [Fact]
    public void Free_fall_with_drag_starts_at_rest_at_height_and_satisfies_its_equation()
    {
        var scenario = new FreeFallScenario();
        var (y, v) = Vertical(scenario, 0);
        Assert.Equal(300, y);
        Assert.Equal(0, v);
        var tau = scenario.Mass / scenario.Drag;
        foreach (var t in new[] { 0.3, 1.0, 4.0, 9.5 })
        {
            var (dy, dv) = CentralDerivative(scenario, t);
            Assert.Equal(Vertical(scenario, t).V, dy, 1e-7);
            Assert.Equal(-scenario.Gravity - (Vertical(scenario, t).V / tau), dv, 1e-6);
        }
    }

    [Fact]
    public void Free_fall_without_drag_is_the_parabola()
    {
        var scenario = new FreeFallScenario { Drag = 0 };
        var (y, v) = Vertical(scenario, 2);
        Assert.Equal(300 - (0.5 * 9.81 * 4), y, 12);
        Assert.Equal(-9.81 * 2, v, 12);
    }

    [Fact]
    public void Free_fall_with_drag_reaches_the_terminal_velocity_minus_g_tau()
    {
        var scenario = new FreeFallScenario { Mass = 0.02, Drag = 0.01 };
        Assert.Equal(-9.81 * 2, Vertical(scenario, 200).V, 10);
    }

    [Theory]
    [InlineData(0.1)] // under-damped, the default
    [InlineData(2.0)] // critically damped: c = 2 sqrt(k m)
    [InlineData(5.0)] // over-damped
    [InlineData(2.0 * (1 + 1e-9))] // just over critical: the over-damped branch must not cancel
    [InlineData(2.0 * (1 - 1e-9))] // just under critical
    public void Mass_spring_damper_satisfies_m_y2_plus_c_y1_plus_k_y_equals_minus_m_g(double damping)
    {
        var scenario = new MassSpringDamperScenario { Damping = damping, Y0 = 0.5, V0 = -1.5, Mass = 1, Stiffness = 1 };
        var (y0, v0) = Vertical(scenario, 0);
        Assert.Equal(0.5, y0, 14);
        Assert.Equal(-1.5, v0, 14);
        foreach (var t in new[] { 0.2, 1.0, 3.7, 12.0 })
        {
            var (y, v) = Vertical(scenario, t);
            var (dy, dv) = CentralDerivative(scenario, t);
            Assert.Equal(v, dy, 1e-7);
            var residual = (scenario.Mass * dv) + (scenario.Damping * v) + (scenario.Stiffness * y) + (scenario.Mass * 9.81);
            Assert.True(Math.Abs(residual) < 1e-6, $"residual {residual} at t={t}");
        }
    }

    [Fact]
    public void Mass_spring_damper_settles_at_minus_m_g_over_k()
    {
        var scenario = new MassSpringDamperScenario { Mass = 2, Stiffness = 4, Damping = 3 };
        Assert.Equal(-2 * 9.81 / 4, Vertical(scenario, 200).Y, 10);
    }

    [Fact]
    public void Near_critical_damping_is_continuous_across_the_three_formulas()
    {
        var below = Vertical(new MassSpringDamperScenario { Damping = 2 * (1 - 1e-12), Y0 = 1 }, 3.3);
        var at = Vertical(new MassSpringDamperScenario { Damping = 2, Y0 = 1 }, 3.3);
        var above = Vertical(new MassSpringDamperScenario { Damping = 2 * (1 + 1e-12), Y0 = 1 }, 3.3);
        Assert.Equal(at.Y, below.Y, 1e-9);
        Assert.Equal(at.Y, above.Y, 1e-9);
        Assert.Equal(at.V, below.V, 1e-9);
        Assert.Equal(at.V, above.V, 1e-9);
    }

    [Fact]
    public void Mass_spring_damper_without_spring_is_a_free_fall_from_y0()
    {
        var scenario = new MassSpringDamperScenario { Stiffness = 0, Damping = 0.5, Mass = 1, Y0 = 3, V0 = 2 };
        var freeFall = new FreeFallScenario { Mass = 1, Drag = 0.5, Height = 3 };
        // Free fall from rest plus the decaying initial velocity: y = y_ff(t) + v0 tau (1 - e^(-t/tau)).
        var t = 2.5;
        var tau = 2.0;
        var expectedY = Vertical(freeFall, t).Y + (2 * tau * (1 - Math.Exp(-t / tau)));
        Assert.Equal(expectedY, Vertical(scenario, t).Y, 12);
    }

    [Theory]
    [InlineData(0.0)]
    [InlineData(0.5)]
    public void Two_mass_chain_matches_an_eigen_decomposition_by_MathNet(double restLength2)
    {
        var scenario = new TwoMassChainScenario { RestLength2 = restLength2, M2 = 1.5, C2 = 0.2, Y1 = -1.3 };
        var a = scenario.SystemMatrix();

        // Homogeneous part: z' = B z with z = (y1, y2, v1, v2) - equilibrium. For a real non-symmetric matrix MathNet
        // returns the real Schur-like form B = V D V^-1, where D holds a 2 x 2 block [[a, b], [-b, a]] for each
        // complex pair a +- i b; exp(D t) is then e^(a t) [[cos b t, sin b t], [-sin b t, cos b t]] per block.
        var b = Matrix<double>.Build.Dense(4, 4, (i, j) => a[i, j]);
        var equilibrium = -b.Solve(Vector<double>.Build.Dense(4, i => a[i, 4]));
        var z0 = Vector<double>.Build.Dense(new[] { scenario.Y1, scenario.Y2, 0, 0 }) - equilibrium;
        var evd = b.Evd();
        var v = evd.EigenVectors;
        var d = evd.D;
        Assert.True((v * d * v.Inverse() - b).InfinityNorm() < 1e-12, "the decomposition reproduces B");
        var modal0 = v.Solve(z0);

        var state = new double[12];
        foreach (var t in new[] { 0.0, 0.7, 3.0, 11.0, 20.0 })
        {
            var expDt = Matrix<double>.Build.Dense(4, 4);
            for (var i = 0; i < 4; i++)
            {
                if (i + 1 < 4 && d[i, i + 1] != 0)
                {
                    double re = d[i, i], im = d[i, i + 1], decay = Math.Exp(re * t);
                    Assert.Equal(-im, d[i + 1, i], 12);
                    expDt[i, i] = decay * Math.Cos(im * t);
                    expDt[i, i + 1] = decay * Math.Sin(im * t);
                    expDt[i + 1, i] = -decay * Math.Sin(im * t);
                    expDt[i + 1, i + 1] = decay * Math.Cos(im * t);
                    i++;
                }
                else
                {
                    expDt[i, i] = Math.Exp(d[i, i] * t);
                }
            }

            var z = (v * expDt * modal0) + equilibrium;
            scenario.ExactState(t, state);
            Assert.Equal(z[0], state[1], 1e-11);
            Assert.Equal(z[1], state[4], 1e-11);
            Assert.Equal(z[2], state[7], 1e-11);
            Assert.Equal(z[3], state[10], 1e-11);
        }
    }

    [Fact]
    public void Two_mass_chain_hangs_at_its_static_equilibrium()
    {
        var scenario = new TwoMassChainScenario();
        var state = new double[12];
        scenario.ExactState(400, state);
        // k1 (y1 + L1) = -(m1 + m2) g and k2 (y1 - y2 - L2) = m2 g.
        Assert.Equal(-1 - (2 * 9.81 / 10), state[1], 9);
        Assert.Equal(state[1] - (9.81 / 10), state[4], 9);
    }

    [Fact]
    public void Scalar_ode_exact_solution_is_the_gaussian()
    {
        var ode = new GaussianDecayOde();
        var y = new double[1];
        var dydt = new double[1];
        foreach (var t in new[] { 0.0, 0.5, 1.0, 2.0 })
        {
            ode.ExactState(t, y);
            Assert.Equal(Math.Exp(-t * t), y[0], 15);
            ode.Evaluate(t, y, dydt);
            var yPlus = new double[1];
            var yMinus = new double[1];
            ode.ExactState(t + H, yPlus);
            ode.ExactState(t - H, yMinus);
            Assert.Equal((yPlus[0] - yMinus[0]) / (2 * H), dydt[0], 1e-7);
        }
    }

    private static (double Y, double V) Vertical(IExactSolution exact, double t)
    {
        var state = new double[6];
        exact.ExactState(t, state);
        return (state[1], state[4]);
    }

    private static (double DY, double DV) CentralDerivative(IExactSolution exact, double t)
    {
        var plus = Vertical(exact, t + H);
        var minus = Vertical(exact, t - H);
        return ((plus.Y - minus.Y) / (2 * H), (plus.V - minus.V) / (2 * H));
    }
}
