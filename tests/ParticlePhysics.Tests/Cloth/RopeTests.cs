using System;
using ParticlePhysics.Cloth;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using Xunit.Abstractions;

namespace ParticlePhysics.Tests.Cloth;

/// <summary>
/// Ropes with bending rigidity EI against Euler-Bernoulli beam theory: a cantilever clamped by pinning its first two
/// points sags mu g L^4 / (8 EI), L from midway between them, converging at second order; rigid motions cost nothing;
/// and the issue's rope, held out horizontally, now hangs as its rigidity says.
/// </summary>
public class RopeTests
{
    private const double G = 9.81;
    private readonly ITestOutputHelper _output;

    public RopeTests(ITestOutputHelper output)
    {
        _output = output;
    }

    [Fact]
    public void A_cantilever_rope_sags_mu_g_L4_over_8_EI_and_converges_at_second_order()
    {
        const double rigidity = 0.5, mass = 0.2; // EI in N m^2; mu = 0.2 kg/m over L = 1 m, and its clamp's half segment
        var sizes = new[] { 10, 20, 40, 80 };
        var errors = new double[sizes.Length];
        for (var k = 0; k < sizes.Length; k++)
        {
            var n = sizes[k];
            var builder = Rope(n, mass, rigidity);
            var world = new ParticleWorld();
            for (var i = 0; i <= n; i++)
            {
                world.AddParticle(new Vector3d((i - 0.5) / (n - 0.5), 0, 0), 1);
            }

            var bending = new QuadraticBending(world);
            RopeBending.AddPolyline(bending, Points(n), 0, rigidity);
            var pinned = new bool[n + 1];
            pinned[0] = pinned[1] = true;
            var w = ClothMeshes.StaticDeflection(bending, builder.ParticleMasses(), pinned, G);
            var mu = builder.TotalMass / builder.Length;
            errors[k] = (w[n] / (-mu * G / (8 * rigidity))) - 1;
            _output.WriteLine($"{n} segments: sag error {errors[k] * 100:F4} %");
        }

        Assert.True(Math.Abs(errors[2]) < 0.05, $"error {errors[2]:P2} at 40 segments");
        for (var k = 0; k + 1 < sizes.Length; k++)
        {
            Assert.InRange(Math.Log2(errors[k] / errors[k + 1]), 1.8, 2.2);
        }
    }

    [Theory]
    [InlineData("implicit-euler", 40)]
    [InlineData("xpbd", 20)]
    public void A_cantilever_rope_stepped_to_rest_sags_as_the_beam(string integrator, int n)
    {
        // Small deflections: EI = 2.45 N m^2 and mu = 0.02 kg/m sag by 1 % of L. Under implicit Euler the segments are
        // stiff springs (a rod's tension is linearised without its dependence on the bending forces it balances, which
        // makes a stiff beam of rods unstable at large steps); under xpbd they are rods, and one sweep per substep makes
        // the beam softer by about (h omega)^2 for its shortest wave, omega = sqrt(EI / mu) / dx^2 = 4400 rad/s at 20
        // segments: 1000 substeps of 1/60 s keep that at 0.5 %.
        const double rigidity = 2.45, mass = 0.02;
        var builder = Rope(n, mass, rigidity);
        builder.Stretch = integrator == "xpbd" ? RopeStretch.Inextensible : RopeStretch.Springs;
        builder.SpringStiffness = 1e5;
        builder.Drag = 0.1 / n;
        var rope = builder.Build();
        var stepper = integrator == "xpbd" ? (IIntegrator)new Xpbd(1000) : new ImplicitEuler { Tolerance = 1e-10 };
        var dt = integrator == "xpbd" ? 1.0 / 60 : 0.05;
        for (var t = 0.0; t < 6; t += dt)
        {
            rope.System.Step(stepper, dt);
        }

        var mu = builder.TotalMass / builder.Length;
        var error = (rope.System.GetPosition(n).Y / (-mu * G / (8 * rigidity))) - 1;
        _output.WriteLine($"{integrator}, {n} segments: sag error {error * 100:F3} %");
        Assert.True(Math.Abs(error) < 0.02, $"error {error:P2}");
    }

    [Fact]
    public void Rigid_motions_of_a_straight_rope_cost_no_energy()
    {
        var world = new ParticleWorld();
        var points = Points(12);
        for (var i = 0; i < points.Length / 3; i++)
        {
            world.AddParticle(new Vector3d(points[3 * i], 0, 0), 1);
        }

        var bending = new QuadraticBending(world);
        RopeBending.AddPolyline(bending, points, 0, 3.0);
        var rotation = global::ParticlePhysics.Constraints.Rotation3d.FromAxisAngle(new Vector3d(0.3, -1, 2), 2.0);
        for (var i = 0; i < world.Count; i++)
        {
            world.SetPosition(i, rotation.Rotate(world.GetPosition(i)) + new Vector3d(1, 2, 3));
        }

        Assert.True(Math.Abs(bending.PotentialEnergy(world.View())) < 1e-12);
    }

    [Fact]
    public void The_issues_rope_sags_less_as_its_rigidity_rises()
    {
        // 1 m, 21 points, clamped at one end and held out horizontally: the tip's height for rising EI.
        var previous = double.NegativeInfinity;
        foreach (var rigidity in new[] { 0.001, 0.01, 0.1, 1.0 })
        {
            var points = new Vector3d[21];
            for (var i = 0; i < points.Length; i++)
            {
                points[i] = new Vector3d(i / 20.0, 0, 0);
            }

            var builder = new RopeBuilder(points) { TotalMass = 0.1, BendingRigidity = rigidity, SpringStiffness = 1e4, Drag = 0.01 };
            builder.Pin(0).Pin(1);
            var rope = builder.Build();
            var stepper = new ImplicitEuler { Tolerance = 1e-8 };
            for (var s = 0; s < 200; s++)
            {
                rope.System.Step(stepper, 0.05);
            }

            var tip = rope.System.GetPosition(20).Y;
            _output.WriteLine($"EI = {rigidity} N m^2: tip at y = {tip:F4} m");
            Assert.True(tip > previous, $"the tip at EI = {rigidity} ({tip}) is not above the one before ({previous})");
            previous = tip;
        }
    }

    /// <summary>n segments, points at (i - 1/2) h, h = 1 / (n - 1/2): L = 1 m from midway between points 0 and 1.</summary>
    private static RopeBuilder Rope(int n, double mass, double rigidity)
    {
        var points = new Vector3d[n + 1];
        for (var i = 0; i <= n; i++)
        {
            points[i] = new Vector3d((i - 0.5) / (n - 0.5), 0, 0);
        }

        var builder = new RopeBuilder(points) { TotalMass = mass * (n / (n - 0.5)), BendingRigidity = rigidity, SpringStiffness = 1e4 };
        builder.Pin(0).Pin(1);
        return builder;
    }

    private static double[] Points(int n)
    {
        var x = new double[3 * (n + 1)];
        for (var i = 0; i <= n; i++)
        {
            x[3 * i] = (i - 0.5) / (n - 0.5);
        }

        return x;
    }
}
