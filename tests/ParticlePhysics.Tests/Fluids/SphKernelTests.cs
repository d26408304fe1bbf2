using System;
using ParticlePhysics.Fluids;
using Xunit;

namespace ParticlePhysics.Tests.Fluids;

/// <summary>The kernel of position-based fluids against quadrature, its closed form and finite differences (independent oracles).</summary>
public class SphKernelTests
{
    [Theory]
    [InlineData(0.02)]
    [InlineData(1.0)]
    public void Spiky_integrates_to_one_over_its_ball(double h)
    {
        var kernel = new SphKernel(h);

        // Composite Simpson over r in [0, h] of 4 pi r^2 W(r), a degree-5 polynomial: its error at 200 intervals is 1e-10.
        const int n = 200;
        var step = h / n;
        var sum = 0.0;
        for (var k = 0; k <= n; k++)
        {
            var r = k * step;
            var weight = k == 0 || k == n ? 1.0 : k % 2 == 1 ? 4.0 : 2.0;
            sum += weight * 4.0 * Math.PI * r * r * kernel.Density(r);
        }

        Assert.Equal(1.0, sum * step / 3.0, 8);
        Assert.Equal(kernel.Density(0.0), kernel.Peak, 12);
        Assert.Equal(0.0, kernel.Density(h));
    }

    [Fact]
    public void The_gradient_is_the_derivative_of_the_kernel_which_is_spiky_and_both_vanish_outside_h()
    {
        const double h = 0.05;
        var kernel = new SphKernel(h);
        double Spiky(double r) => r < h ? 15.0 / (Math.PI * Math.Pow(h, 6)) * Math.Pow(h - r, 3) : 0.0;
        foreach (var r in new[] { 0.1 * h, 0.37 * h, 0.5 * h, 0.9 * h })
        {
            Assert.Equal(Spiky(r), kernel.Density(r), Spiky(r) * 1e-13);
            const double e = 1e-7;
            var derivative = (kernel.Density(r + e) - kernel.Density(r - e)) / (2 * e);

            // grad W = -factor * r_vec, so dW/dr = -factor * r.
            Assert.Equal(derivative, -kernel.GradientOverDistance(r) * r, Math.Abs(derivative) * 1e-6);
        }

        Assert.Equal(0.0, kernel.GradientOverDistance(h));
        Assert.Equal(0.0, kernel.GradientOverDistance(0.0));
    }

    [Fact]
    public void A_radius_that_is_not_positive_and_finite_is_refused()
    {
        Assert.Throws<ArgumentOutOfRangeException>(() => new SphKernel(0.0));
        Assert.Throws<ArgumentOutOfRangeException>(() => new SphKernel(double.NaN));
        Assert.Throws<ArgumentOutOfRangeException>(() => new SphKernel(1e-60));
    }
}
