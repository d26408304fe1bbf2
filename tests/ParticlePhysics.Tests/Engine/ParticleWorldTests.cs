using System;
using System.Numerics;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Engine;

/// <summary>The particle store: layout, pinning, growth, forces added and removed, read-out for rendering.</summary>
public class ParticleWorldTests
{
    [Theory]
    [MemberData(nameof(DeterminismAndAllocationTests.Integrators), MemberType = typeof(DeterminismAndAllocationTests))]
    public void Pinned_particles_never_move_whatever_the_integrator(string integrator)
    {
        var system = new ClothScenario().Build();
        var corner = system.GetPosition(10);
        StateMetrics.Run(system, IntegratorCatalog.Create(integrator), 0.001, 300);
        Assert.Equal(Vector3d.Zero, system.GetPosition(0));
        Assert.Equal(corner, system.GetPosition(10));
        Assert.Equal(Vector3d.Zero, system.GetVelocity(0));
        Assert.True(system.GetPosition(60).Y < -0.01, "the free particles fall");
    }

    [Fact]
    public void The_state_vector_is_positions_then_velocities_and_survives_growth()
    {
        var system = new ParticleWorld();
        for (var i = 0; i < 37; i++)
        {
            system.AddParticle(new Vector3d(i, 2 * i, 3 * i), new Vector3d(-i, -2 * i, -3 * i), 1 + i);
            if (i == 20)
            {
                _ = system.State; // compacts; later additions must grow it again without losing anything
            }
        }

        var state = system.State;
        Assert.Equal(6 * 37, state.Length);
        for (var i = 0; i < 37; i++)
        {
            Assert.Equal(new Vector3d(i, 2 * i, 3 * i), system.GetPosition(i));
            Assert.Equal(2.0 * i, state[(3 * i) + 1]);
            Assert.Equal(-3.0 * i, state[(3 * 37) + (3 * i) + 2]);
            Assert.Equal(1.0 + i, system.Masses[i]);
        }
    }

    [Fact]
    public void Each_particle_has_its_own_mass()
    {
        var system = new ParticleWorld();
        system.AddParticle(Vector3d.Zero, 1);
        system.AddParticle(Vector3d.Zero, 4);
        system.AddForce(new Gravity());
        var force = new ZeroLengthSprings(system);
        force.AddAnchored(0, new Vector3d(1, 0, 0), 2);
        force.AddAnchored(1, new Vector3d(1, 0, 0), 2);
        system.AddForce(force);
        var derivative = new double[12];
        system.Evaluate(0, system.State, derivative);
        Assert.Equal(2.0, derivative[6]);
        Assert.Equal(0.5, derivative[9]);
        Assert.Equal(-9.81, derivative[7]);
        Assert.Equal(-9.81, derivative[10], 14);
    }

    [Fact]
    public void Forces_can_be_added_changed_and_removed_between_steps()
    {
        var system = new ParticleWorld();
        system.AddParticle(Vector3d.Zero, 2);
        var gravity = new Gravity();
        system.AddForce(gravity);
        var rk4 = new RungeKutta4();
        system.Step(rk4, 0.1);
        Assert.Equal(-9.81 * 0.1, system.GetVelocity(0).Y, 12);

        gravity.Acceleration = new Vector3d(1, 0, 0);
        system.Step(rk4, 0.1);
        Assert.Equal(0.1, system.GetVelocity(0).X, 12);

        Assert.True(system.RemoveForce(gravity));
        Assert.False(system.RemoveForce(gravity));
        var before = system.GetVelocity(0);
        system.Step(rk4, 0.1);
        Assert.Equal(before, system.GetVelocity(0));
    }

    [Fact]
    public void Unpinning_frees_a_particle_with_its_own_mass()
    {
        var system = new ParticleWorld();
        system.AddParticle(Vector3d.Zero, 2);
        system.AddForce(new Gravity());
        system.Pin(0);
        system.Step(new ExplicitEuler(), 0.1);
        Assert.Equal(Vector3d.Zero, system.GetPosition(0));
        system.Unpin(0);
        system.Step(new ExplicitEuler(), 0.1);
        Assert.Equal(-0.981, system.GetVelocity(0).Y, 12);
    }

    [Fact]
    public void Positions_convert_to_single_precision_vectors_for_rendering()
    {
        var system = new ClothScenario { Resolution = 0.5 }.Build();
        var vertices = new Vector3[system.Count];
        system.CopyPositionsTo(vertices);
        Assert.Equal(new Vector3(0.5f, 0, 1f), vertices[7]);
        Assert.Equal(system.GetPosition(7).ToVector3(), vertices[7]);
        Assert.Throws<ArgumentException>("destination", () => system.CopyPositionsTo(new Vector3[3]));
    }

    [Fact]
    public void The_cloth_has_the_contract_topology()
    {
        var cloth = new ClothScenario();
        var system = cloth.Build();
        Assert.Equal(11, cloth.ParticlesPerSide);
        Assert.Equal(121, system.Count);
        var springs = Assert.Single(system.Forces, f => f is SpringNetwork) as SpringNetwork;
        Assert.Equal(ClothScenario.SpringCount(11), springs!.Count);
        Assert.Equal((2 * 11 * 10) + (2 * 10 * 10) + (2 * 11 * 9), springs.Count);
        Assert.True(system.IsPinned(0) && system.IsPinned(10) && !system.IsPinned(11));
        Assert.Equal(new Vector3d(0.30000000000000004, 0, 0.2), system.GetPosition(25));
        Assert.Equal(1.0 / 121, system.GetMass(5));
        Assert.Equal(Math.Sqrt(2) * 0.1, springs.GetRestLength(2), 15);
    }

    [Theory]
    [InlineData(1.0, 0.3)]
    [InlineData(1.0, 0.15)]
    [InlineData(1.0, 2.0)]
    public void A_resolution_that_does_not_divide_the_size_is_refused(double size, double resolution)
    {
        var cloth = new ClothScenario { Size = size, Resolution = resolution };
        var ex = Assert.Throws<ArgumentException>("Resolution", () => cloth.Build());
        Assert.Contains("does not divide", ex.Message, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData(1.0, 1.0, 2)]
    [InlineData(1.0, 0.5, 3)]
    [InlineData(1.0, 0.1, 11)]
    [InlineData(3.0, 0.1, 31)]
    public void The_course_resolutions_give_whole_grids(double size, double resolution, int n)
    {
        Assert.Equal(n, new ClothScenario { Size = size, Resolution = resolution }.ParticlesPerSide);
    }

    [Fact]
    public void Vector3d_prints_in_the_invariant_culture()
    {
        var previous = System.Globalization.CultureInfo.CurrentCulture;
        try
        {
            System.Globalization.CultureInfo.CurrentCulture = new System.Globalization.CultureInfo("fr-FR");
            Assert.Equal("(0.5, -1, 1E-05)", new Vector3d(0.5, -1, 1e-5).ToString());
        }
        finally
        {
            System.Globalization.CultureInfo.CurrentCulture = previous;
        }
    }
}
