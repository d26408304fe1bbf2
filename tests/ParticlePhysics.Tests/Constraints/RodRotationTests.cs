using System;
using ParticlePhysics.Constraints;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Tests.Constraints;

/// <summary>
/// Uniform rotation on a rod (no gravity: a particle of speed u on a circle of radius L, omega = u / L), whose steps
/// have closed forms. Semi-implicit Euler with the rod closed as SHAKE does is the constrained symplectic Euler method:
/// the speed stays u exactly and the angle advances asin(h omega) per step. Implicit Euler with the tension's geometric
/// stiffness is backward Euler on the rotation, as on the oscillator y' = i omega y: each step shrinks the speed by
/// 1 / sqrt(1 + (h omega)^2) and advances the angle by atan(h omega), omega that of the step's start. Before issue 27's item 4 both took the tension
/// explicitly, and every step sped the particle up by 1 / sqrt(1 - (h omega)^2 + (h omega)^4): the runaway of the
/// chains in its simplest form.
/// </summary>
public class RodRotationTests
{
    private const double Radius = 0.5;
    private const double Speed = 3;
    private const double Mass = 2;

    [Theory]
    [InlineData(0.01)]
    [InlineData(0.05)]
    public void Semi_implicit_euler_keeps_the_speed_of_a_uniform_rotation_exactly(double h)
    {
        var world = Rotation();
        var omega = Speed / Radius;
        const int steps = 100;
        for (var s = 0; s < steps; s++)
        {
            world.Step(new SemiImplicitEuler(), h);
        }

        var (angle, speed, radius) = Observe(world);
        Assert.Equal(Speed, speed, 1e-11);
        Assert.Equal(Radius, radius, 1e-12);
        Assert.Equal(Wrap(steps * Math.Asin(h * omega)), angle, 1e-10);
    }

    [Theory]
    [InlineData(0.2)]
    [InlineData(1.0)]
    public void A_rod_that_turns_faster_than_shake_can_follow_keeps_its_length_and_never_speeds_up(double h)
    {
        // h omega > 1: no point of the line along the start's gradient lies on the circle, so SHAKE's iteration stalls,
        // its last iteration is undone and the Newton projection finishes. The step loses energy instead of gaining it.
        var world = Rotation();
        for (var s = 0; s < 200; s++)
        {
            world.Step(new SemiImplicitEuler(), h);
            var (_, speed, radius) = Observe(world);
            Assert.Equal(Radius, radius, 1e-12);
            Assert.True(speed <= Speed * (1 + 1e-12), $"step {s}: {speed:R} m/s");
        }
    }

    [Theory]
    [InlineData(0.01)]
    [InlineData(0.05)]
    public void Implicit_euler_damps_a_uniform_rotation_as_backward_euler_damps_an_oscillator(double h)
    {
        // Each step at the speed u_n it starts from: u_(n+1) = u_n / sqrt(1 + (h u_n / L)^2), the angle + atan(h u_n / L).
        var world = Rotation();
        var implicitEuler = new ImplicitEuler();
        double expectedSpeed = Speed, expectedAngle = 0;
        const int steps = 100;
        for (var s = 0; s < steps; s++)
        {
            world.Step(implicitEuler, h);
            var turn = h * expectedSpeed / Radius;
            expectedAngle += Math.Atan(turn);
            expectedSpeed /= Math.Sqrt(1 + (turn * turn));
        }

        var (angle, speed, radius) = Observe(world);
        Assert.Equal(expectedSpeed, speed, 1e-10);
        Assert.Equal(Radius, radius, 1e-12);
        Assert.Equal(Wrap(expectedAngle), angle, 1e-9);
    }

    [Fact]
    public void The_rods_linearisation_is_the_tension_per_unit_length_as_a_zero_length_spring()
    {
        // J = a K with K's blocks -k I on each end and +k I between them, k = T / |d| = -lambda for a rod that pulls, 0
        // for one that pushes; symmetric and negative semi-definite. Products and blocks need a Linearize of the links
        // there are.
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(0.3, -0.4, 0), new Vector3d(1, 0.5, 0), 1);
        world.AddParticle(new Vector3d(0.3, -0.9, 0.1), new Vector3d(-0.5, 1, 0.2), 2);
        world.AddForce(new Forces.Gravity());
        var rods = new RodNetwork(world);
        rods.AddAnchoredRod(0, Vector3d.Zero, 0.5);
        rods.AddRod(0, 1, Math.Sqrt(0.26));
        world.AddConstraints(rods);
        IForceJacobian jacobian = rods;
        var n = world.CoordinateCount;
        Assert.Throws<InvalidOperationException>(() => jacobian.AddJacobianProduct(new double[n], new double[n]));

        _ = world.AccumulateForces(0, world.Positions, world.Velocities);
        const double scale = 0.25;
        var kv = new double[n];
        jacobian.Linearize(world.View(), scale, 7.0, kv);
        var columns = new double[n][];
        for (var c = 0; c < n; c++)
        {
            var unit = new double[n];
            unit[c] = 1;
            columns[c] = new double[n];
            jacobian.AddJacobianProduct(unit, columns[c]);
        }

        var blocks = new double[3 * n];
        jacobian.AddDiagonalBlocks(blocks);
        var k0 = rods.GetTension(0) / world.GetPosition(0).Length;
        var k1 = rods.GetTension(1) / (world.GetPosition(0) - world.GetPosition(1)).Length;
        Assert.True(k0 > 0 && k1 > 0, $"both rods pull: {k0}, {k1}");
        for (var a = 0; a < 3; a++)
        {
            Assert.Equal(-scale * (k0 + k1), columns[a][a], 12);
            Assert.Equal(scale * k1, columns[a][3 + a], 12);
            Assert.Equal(-scale * k1, columns[3 + a][3 + a], 12);
            Assert.Equal(columns[a][a], blocks[(4 * a)], 15);
            Assert.Equal(columns[3 + a][3 + a], blocks[9 + (4 * a)], 15);
        }

        for (var a = 0; a < n; a++)
        {
            for (var b = 0; b < n; b++)
            {
                Assert.Equal(columns[a][b], columns[b][a], 15);
            }
        }

        // (df/dx) v, unscaled: -k0 v_0 - k1 (v_0 - v_1) on particle 0.
        Assert.Equal((-k0 * 1) - (k1 * (1 - -0.5)), kv[0], 12);

        rods.AddRod(0, 1, 0.6);
        Assert.Throws<InvalidOperationException>(() => jacobian.AddJacobianProduct(new double[n], new double[n]));
    }

    private static ParticleWorld Rotation()
    {
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(Radius, 0, 0), new Vector3d(0, Speed, 0), Mass);
        var rods = new RodNetwork(world);
        rods.AddAnchoredRod(0, Vector3d.Zero, Radius);
        world.AddConstraints(rods);
        return world;
    }

    private static (double Angle, double Speed, double Radius) Observe(ParticleWorld world)
    {
        var x = world.GetPosition(0);
        return (Math.Atan2(x.Y, x.X), world.GetVelocity(0).Length, x.Length);
    }

    private static double Wrap(double angle) => Math.Atan2(Math.Sin(angle), Math.Cos(angle));
}
