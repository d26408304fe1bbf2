using System;
using System.Collections.Generic;
using ParticlePhysics.Cloth;
using ParticlePhysics.Forces;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Cloth;

/// <summary>The cloth builder: grid, masses, pins, spring families, and the course's cloth built on it.</summary>
public class ClothBuilderTests
{
    [Fact]
    public void The_course_cloth_has_the_contracts_springs_in_the_contracts_order()
    {
        // SCENARIOS.md, listed per particle in index order: structural right and down, shear, bend right and down.
        var system = new ClothScenario { Size = 0.2, Resolution = 0.1 }.Build();
        var springs = Assert.IsType<SpringNetwork>(system.Forces[0]);
        Assert.IsType<LinearDrag>(system.Forces[1]);
        Assert.IsType<Gravity>(system.Forces[2]);
        var d = 0.1 * Math.Sqrt(2);
        var expected = new List<(int, int, double)>
        {
            (0, 1, 0.1), (0, 3, 0.1), (0, 4, d), (1, 3, d), (0, 2, 0.2), (0, 6, 0.2),
            (1, 2, 0.1), (1, 4, 0.1), (1, 5, d), (2, 4, d), (1, 7, 0.2),
            (2, 5, 0.1), (2, 8, 0.2),
            (3, 4, 0.1), (3, 6, 0.1), (3, 7, d), (4, 6, d), (3, 5, 0.2),
            (4, 5, 0.1), (4, 7, 0.1), (4, 8, d), (5, 7, d),
            (5, 8, 0.1),
            (6, 7, 0.1), (6, 8, 0.2),
            (7, 8, 0.1),
        };
        Assert.Equal(expected.Count, springs.Count);
        for (var s = 0; s < springs.Count; s++)
        {
            var (first, second) = springs.GetEnds(s);
            Assert.Equal((expected[s].Item1, expected[s].Item2), (first, second));
            Assert.Equal(expected[s].Item3, springs.GetRestLength(s));
        }
    }

    [Fact]
    public void A_rectangle_has_its_particles_masses_and_spring_families()
    {
        var cloth = new ClothBuilder { Rows = 4, Columns = 7, Spacing = 0.25, TotalMass = 2.8, Origin = new Vector3d(1, 2, 3) }.Build();
        var system = cloth.System;
        Assert.Equal(28, system.Count);
        Assert.Equal(new Vector3d(1 + (5 * 0.25), 2, 3 + (2 * 0.25)), system.GetPosition(cloth.ParticleIndex(2, 5)));
        Assert.Equal(2.8 / 28, system.GetMass(13));
        int rows = 4, cols = 7;
        var structural = (rows * (cols - 1)) + (cols * (rows - 1));
        var shear = 2 * (rows - 1) * (cols - 1);
        var bend = (rows * (cols - 2)) + (cols * (rows - 2));
        Assert.Equal(structural + shear + bend, cloth.Springs.Count);

        var builder = new ClothBuilder { Rows = 4, Columns = 7 };
        builder.Shear.Enabled = false;
        Assert.Equal(structural + bend, builder.Build().Springs.Count);
        builder.Bend.Enabled = false;
        Assert.Equal(structural, builder.Build().Springs.Count);
        builder.Structural.Enabled = false;
        builder.Shear.Enabled = true;
        Assert.Equal(shear, builder.Build().Springs.Count);
    }

    [Fact]
    public void Each_family_has_its_own_stiffness_and_damping()
    {
        var builder = new ClothBuilder { Rows = 2, Columns = 3, Spacing = 1, Pinning = ClothPinning.None, Gravity = 0, Drag = 0 };
        builder.Structural.Stiffness = 0;
        builder.Bend.Stiffness = 0;
        builder.Structural.Damping = 0;
        builder.Bend.Damping = 0;
        builder.Shear.Stiffness = 7;
        builder.Shear.Damping = 0;
        var cloth = builder.Build();

        // Stretch the shear spring (0, 0)-(1, 1) by 0.5 along its axis: only it pulls, with k = 7.
        var system = cloth.System;
        var u = new Vector3d(1, 0, 1) / Math.Sqrt(2);
        system.SetPosition(0, system.GetPosition(0) - (0.5 * u));
        var forces = system.AccumulateForces(0, system.Positions, system.Velocities);
        Assert.Equal(7 * 0.5 * u.X, forces[0], 12);
        Assert.Equal(7 * 0.5 * u.Z, forces[2], 12);
    }

    [Fact]
    public void Pins_come_from_the_preset_and_from_any_list()
    {
        var corners = new ClothBuilder { Rows = 3, Columns = 4 }.Build().System;
        Assert.Equal(new[] { 0, 3 }, Pinned(corners));
        var edge = new ClothBuilder { Rows = 3, Columns = 4, Pinning = ClothPinning.Edge }.Build().System;
        Assert.Equal(new[] { 0, 1, 2, 3 }, Pinned(edge));
        var custom = new ClothBuilder { Rows = 3, Columns = 4, Pinning = ClothPinning.None }.Pin(2, 3).Pin(5).PinColumn(0).Build().System;
        Assert.Equal(new[] { 0, 4, 5, 8, 11 }, Pinned(custom));
        var far = new ClothBuilder { Rows = 3, Columns = 4, Pinning = ClothPinning.None }.PinRow(2).Build().System;
        Assert.Equal(new[] { 8, 9, 10, 11 }, Pinned(far));
    }

    [Fact]
    public void A_cloth_added_to_a_shared_system_follows_its_particles_and_drags_only_itself()
    {
        var system = new ParticleWorld();
        system.AddParticle(new Vector3d(5, 5, 5), 1);
        var cloth = new ClothBuilder { Rows = 2, Columns = 2, Drag = 0.3 }.AddTo(system);
        Assert.Equal(1, cloth.FirstParticle);
        Assert.Equal(5, system.Count);
        Assert.True(system.IsPinned(1) && system.IsPinned(2) && !system.IsPinned(0));
        Assert.Null(cloth.Gravity);
        Assert.Equal(new[] { 1, 2, 3, 4 }, cloth.Drag.Particles);
        Assert.Equal(4, cloth.ParticleIndex(1, 1));
        Assert.Equal(2, system.Forces.Count);
    }

    [Fact]
    public void The_scenario_builds_the_same_system_as_its_builder()
    {
        var scenario = new ClothScenario { Resolution = 0.25, Stiffness = 80, Damping = 0.2, Pinning = ClothPinning.Edge };
        var a = scenario.Build();
        var b = scenario.CreateBuilder().Build().System;
        Assert.Equal(StateMetrics.BitHash(a.State), StateMetrics.BitHash(b.State));
        StateMetrics.Run(a, new ParticlePhysics.Integrators.RungeKutta4(), 0.001, 20);
        StateMetrics.Run(b, new ParticlePhysics.Integrators.RungeKutta4(), 0.001, 20);
        Assert.Equal(StateMetrics.BitHash(a.State), StateMetrics.BitHash(b.State));
    }

    [Fact]
    public void Bad_settings_are_refused_with_their_names()
    {
        var builder = new ClothBuilder();
        Assert.Equal("Rows", Assert.Throws<ArgumentOutOfRangeException>(() => builder.Rows = 1).ParamName);
        Assert.Equal("Columns", Assert.Throws<ArgumentOutOfRangeException>(() => builder.Columns = 4096).ParamName);
        Assert.Equal("Spacing", Assert.Throws<ArgumentOutOfRangeException>(() => builder.Spacing = double.NaN).ParamName);
        Assert.Equal("TotalMass", Assert.Throws<ArgumentOutOfRangeException>(() => builder.TotalMass = 0).ParamName);
        Assert.Equal("Stiffness", Assert.Throws<ArgumentOutOfRangeException>(() => builder.Shear.Stiffness = -1).ParamName);
        Assert.Equal("row", Assert.Throws<ArgumentOutOfRangeException>(() => builder.Pin(11, 0)).ParamName);
        Assert.Equal("particle", Assert.Throws<ArgumentOutOfRangeException>(() => builder.Pin(121)).ParamName);
        builder.Pin(120);
        builder.Rows = 5;
        Assert.Throws<InvalidOperationException>(() => builder.Build());
    }

    [Fact]
    public void A_pinning_that_is_no_preset_is_refused_before_anything_is_added()
    {
        // Issue 10, item 6: the builder took any enum value, then AddTo added 9 particles and threw.
        var world = WorldWithOneParticle();
        var builder = new ClothBuilder { Rows = 3, Columns = 3 };
        Assert.Equal("Pinning", Assert.Throws<ArgumentOutOfRangeException>(() => builder.Pinning = (ClothPinning)7).ParamName);
        builder.AddTo(world);
        Assert.Equal(10, world.Count);
    }

    [Theory]
    [InlineData(11, 1e308, 1.0)]    // the third particle's x overflows: AddTo used to add 2 particles, then throw
    [InlineData(2, 1.5e308, 1.0)]   // four finite corners, but the shear springs' rest length r sqrt(2) overflows
    [InlineData(11, 0.1, 1e-307)]   // 121 particles of 8.3e-310 kg: each inverse mass is infinite
    public void A_cloth_that_cannot_be_added_whole_leaves_the_world_as_it_was(int side, double spacing, double totalMass)
    {
        var world = WorldWithOneParticle();
        var before = StateMetrics.BitHash(world.State);
        var builder = new ClothBuilder { Rows = side, Columns = side, Spacing = spacing, TotalMass = totalMass };
        var e = Assert.Throws<InvalidOperationException>(() => builder.AddTo(world));
        Assert.Contains(totalMass < 1 ? "TotalMass" : "Spacing", e.Message, StringComparison.Ordinal);
        Assert.Equal(1, world.Count);
        Assert.Empty(world.Forces);
        Assert.Equal(before, StateMetrics.BitHash(world.State));
        Assert.Throws<InvalidOperationException>(() => builder.Build());
    }

    [Fact]
    public void A_total_mass_whose_inverse_overflows_is_refused_by_the_setter()
    {
        var builder = new ClothBuilder();
        Assert.Equal("TotalMass", Assert.Throws<ArgumentOutOfRangeException>(() => builder.TotalMass = 1e-322).ParamName);
        Assert.Equal(1.0, builder.TotalMass);
    }

    private static ParticleWorld WorldWithOneParticle()
    {
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(5, 5, 5), 1);
        return world;
    }

    private static int[] Pinned(ParticleWorld system)
    {
        var pinned = new List<int>();
        for (var i = 0; i < system.Count; i++)
        {
            if (system.IsPinned(i))
            {
                pinned.Add(i);
            }
        }

        return pinned.ToArray();
    }
}
