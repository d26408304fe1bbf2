using System;
using ParticlePhysics.Numerics;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Tests.Physics;

/// <summary>
/// K(k) and Jacobi's sn, cn, dn against known values and identities, independently of any integrator: the pendulum's
/// exact solution stands on them.
/// </summary>
public class JacobiEllipticTests
{
    [Fact]
    public void K_matches_its_known_values()
    {
        Assert.Equal(Math.PI / 2, JacobiElliptic.CompleteK(0), 1e-15);

        // K(1 / sqrt 2) = Gamma(1/4)^2 / (4 sqrt(pi)), the lemniscatic case.
        Assert.Equal(1.8540746773013719, JacobiElliptic.CompleteK(Math.Sqrt(0.5)), 1e-14);

        // K(sin 60 deg), m = 0.75: 2.1565156474996432.
        Assert.Equal(2.1565156474996432, JacobiElliptic.CompleteK(Math.Sin(Math.PI / 3)), 1e-13);

        // Near k = 1, K = ln(4 / k') + (k'^2 / 4) (ln(4 / k') - 1) + O(k'^4 ln k').
        var kPrime = 1e-3;
        var k = Math.Sqrt((1 - kPrime) * (1 + kPrime));
        var log = Math.Log(4 / kPrime);
        Assert.Equal(log + (kPrime * kPrime / 4 * (log - 1)), JacobiElliptic.CompleteK(k), 1e-9);
    }

    [Fact]
    public void The_contracts_periods_are_4_K_over_w()
    {
        var swing = new PendulumScenario();
        Assert.Equal(2.367842, swing.Period, 1e-6);
        Assert.Equal(2.006067, swing.SmallSwingPeriod, 1e-6);
        Assert.Equal(2.006067, new PendulumScenario { Angle = 1e-4 }.Period, 1e-6);
    }

    [Theory]
    [InlineData(0.0)]
    [InlineData(0.3)]
    [InlineData(0.7071067811865476)]
    [InlineData(0.95)]
    [InlineData(0.999)]
    public void Sn_cn_dn_satisfy_their_identities_and_derivatives(double k)
    {
        var kk = JacobiElliptic.CompleteK(k);
        var (sn, cn, dn) = JacobiElliptic.Functions(kk, k);
        Assert.Equal(1, sn, 1e-14);
        Assert.Equal(0, cn, 1e-13);
        Assert.Equal(Math.Sqrt(1 - (k * k)), dn, 1e-13);

        // sn(K / 2) = 1 / sqrt(1 + k').
        var half = JacobiElliptic.Functions(kk / 2, k);
        Assert.Equal(1 / Math.Sqrt(1 + Math.Sqrt(1 - (k * k))), half.Sn, 1e-14);

        const double h = 1e-5;
        foreach (var u in new[] { -7.3, -1.1, 0.2, 0.9, 2.5, 11.0, 40.0 })
        {
            var (s, c, d) = JacobiElliptic.Functions(u, k);
            Assert.Equal(1, (s * s) + (c * c), 1e-14);
            Assert.Equal(1, (d * d) + (k * k * s * s), 1e-14);

            // d sn / du = cn dn, d cn / du = -sn dn, d dn / du = -k^2 sn cn, by central differences.
            var plus = JacobiElliptic.Functions(u + h, k);
            var minus = JacobiElliptic.Functions(u - h, k);
            Assert.Equal(c * d, (plus.Sn - minus.Sn) / (2 * h), 1e-8);
            Assert.Equal(-s * d, (plus.Cn - minus.Cn) / (2 * h), 1e-8);
            Assert.Equal(-k * k * s * c, (plus.Dn - minus.Dn) / (2 * h), 1e-8);

            // Periods: sn(u + 2K) = -sn(u), sn(u + 4K) = sn(u).
            Assert.Equal(-s, JacobiElliptic.Functions(u + (2 * kk), k).Sn, 1e-13);
            Assert.Equal(s, JacobiElliptic.Functions(u + (4 * kk), k).Sn, 1e-13);
        }
    }

    [Fact]
    public void The_limits_are_the_circular_and_hyperbolic_functions()
    {
        foreach (var u in new[] { -2.0, 0.5, 3.0 })
        {
            var circular = JacobiElliptic.Functions(u, 0);
            Assert.Equal(Math.Sin(u), circular.Sn, 1e-15);
            Assert.Equal(Math.Cos(u), circular.Cn, 1e-15);

            // At k -> 1, sn -> tanh and cn -> sech (with O(k'^2) corrections).
            var nearOne = JacobiElliptic.Functions(u, Math.Sqrt(1 - 1e-12));
            Assert.Equal(Math.Tanh(u), nearOne.Sn, 1e-9);
            Assert.Equal(1 / Math.Cosh(u), nearOne.Cn, 1e-9);
        }
    }

    [Fact]
    public void The_pendulums_exact_solution_satisfies_its_equation()
    {
        // theta'' = -(g / L) sin theta, checked by central differences of the angle and of its rate.
        foreach (var angle in new[] { 30.0, 90.0, 120.0, 170.0 })
        {
            var scenario = new PendulumScenario { Angle = angle, Length = 0.7 };
            var (theta0, rate0) = scenario.ExactAngle(0);
            Assert.Equal(angle * Math.PI / 180, theta0, 1e-13);
            Assert.Equal(0, rate0, 1e-13);
            const double h = 1e-5;
            foreach (var t in new[] { 0.1, 0.77, 1.9, 6.3 })
            {
                var (theta, rate) = scenario.ExactAngle(t);
                var plus = scenario.ExactAngle(t + h);
                var minus = scenario.ExactAngle(t - h);
                Assert.Equal(rate, (plus.Angle - minus.Angle) / (2 * h), 1e-7);
                Assert.Equal(-scenario.Gravity / scenario.Length * Math.Sin(theta), (plus.Rate - minus.Rate) / (2 * h), 1e-6);
            }

            // Back at the start after one period.
            Assert.Equal(theta0, scenario.ExactAngle(scenario.Period).Angle, 1e-10);
        }
    }

    [Fact]
    public void Out_of_range_moduli_are_refused()
    {
        Assert.Throws<ArgumentOutOfRangeException>(() => JacobiElliptic.CompleteK(1));
        Assert.Throws<ArgumentOutOfRangeException>(() => JacobiElliptic.Functions(0.5, -0.1));
        Assert.Throws<ArgumentOutOfRangeException>(() => JacobiElliptic.CompleteK(double.NaN));
    }
}
