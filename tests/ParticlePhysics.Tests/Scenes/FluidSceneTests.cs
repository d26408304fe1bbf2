using System;
using System.Linq;
using ParticlePhysics.Contacts;
using ParticlePhysics.Fluids;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenes;
using ParticlePhysics.Tests.Fluids;

namespace ParticlePhysics.Tests.Scenes;

/// <summary>The scene kind <c>fluid</c>: a block filled by the lattice rule, the library's position-based fluid.</summary>
public class FluidSceneTests
{
    private const string Tank = """
        "colliders": [
          { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0] },
          { "type": "plane", "point": [0, 0, 0], "normal": [1, 0, 0] },
          { "type": "plane", "point": [0.08, 0, 0], "normal": [-1, 0, 0] },
          { "type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1] },
          { "type": "plane", "point": [0, 0, 0.04], "normal": [0, 0, -1] }]
        """;

    [Fact]
    public void A_block_fills_from_min_to_max_with_a_mass_of_density_h_cubed_and_a_radius_of_h_over_two()
    {
        var scene = Scene.Parse("""
            { "objects": [{ "type": "fluid", "box": { "min": [0, 1, 0], "max": [0.3, 1.2, 0.1] }, "spacing": 0.1, "density": 800, "viscosity": 0.1, "vorticity": 0.2 }] }
            """);
        var world = scene.Build();

        Assert.Equal(3 * 2 * 1, world.Count);
        for (var i = 0; i < world.Count; i++)
        {
            var expected = new Vector3d(0.05 + (0.1 * (i % 3)), 1.05 + (0.1 * (i / 3)), 0.05);
            Assert.True((world.GetPosition(i) - expected).Length < 1e-15, $"particle {i} at {world.GetPosition(i)}, not {expected}");
            Assert.Equal(0.8, world.GetMass(i), 14);
            Assert.Equal(0.05, world.GetRadius(i));
        }

        var fluid = Assert.Single(world.Constraints.OfType<PositionBasedFluid>());
        Assert.Equal(6, fluid.Count);
        Assert.Equal(800, fluid.RestDensity);
        Assert.Equal(0.1, fluid.Viscosity);
        Assert.Equal(0.2, fluid.Vorticity);
        Assert.Contains("fluid particles: 6", scene.Describe(), StringComparison.Ordinal);
    }

    [Fact]
    public void Blocks_of_one_water_are_one_fluid_and_a_different_liquid_is_another()
    {
        var world = Scene.Parse("""
            { "objects": [
                { "type": "fluid", "box": { "min": [0, 0, 0], "max": [0.2, 0.2, 0.2] }, "spacing": 0.1 },
                { "type": "fluid", "box": { "min": [1, 0, 0], "max": [1.2, 0.2, 0.2] }, "spacing": 0.1 },
                { "type": "fluid", "box": { "min": [2, 0, 0], "max": [2.2, 0.2, 0.2] }, "spacing": 0.1, "density": 900 }],
              "colliders": [{ "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0] }] }
            """).Build();

        var fluids = world.Constraints.OfType<PositionBasedFluid>().ToArray();
        Assert.Equal(2, fluids.Length);
        Assert.Equal(16, fluids[0].Count);
        Assert.Equal(8, fluids[1].Count);
        var contacts = Assert.Single(world.Constraints.OfType<ContactSet>());
        Assert.All(fluids, f => Assert.Same(contacts, f.Boundary));
        Assert.True(world.Constraints.ToList().IndexOf(contacts) > world.Constraints.ToList().IndexOf(fluids[1]), "the fluids are projected before the contacts");
    }

    [Fact]
    public void Water_in_a_tank_of_planes_steps_to_the_same_bits_as_the_same_fluid_built_with_the_library()
    {
        var scene = Scene.Parse("{ \"objects\": [{ \"type\": \"fluid\", \"box\": { \"min\": [0, 0, 0], \"max\": [0.08, 0.06, 0.04] }, \"spacing\": 0.01 }], " + Tank + " }");
        var fromScene = scene.Build();
        var walls = new[] { FluidTank.Floor() }.Concat(FluidTank.Sides(0.08, 0.04)).ToArray();
        var (byHand, fluid) = FluidTank.Fill(0.01, Vector3d.Zero, new Vector3d(0.08, 0.06, 0.04), walls);
        Assert.Equal(8 * 6 * 4, byHand.Count);
        Assert.Equal(byHand.Count, fromScene.Count);

        var integrator = IntegratorCatalog.Create(scene.Settings.Integrator, scene.Settings.Tolerance, scene.Settings.Substeps);
        var xpbd = new Xpbd(scene.Settings.Substeps);
        for (var step = 0; step < 30; step++)
        {
            fromScene.Step(integrator, scene.Settings.TimeStep);
            byHand.Step(xpbd, scene.Settings.TimeStep);
        }

        for (var i = 0; i < byHand.Count; i++)
        {
            Assert.Equal(byHand.GetPosition(i), fromScene.GetPosition(i));
            Assert.Equal(byHand.GetVelocity(i), fromScene.GetVelocity(i));
        }

        // And it is water at rest in its tank: no particle left the box, and none is compressed by more than 3 %.
        for (var i = 0; i < fromScene.Count; i++)
        {
            var p = fromScene.GetPosition(i);
            Assert.True(p.X > 0 && p.X < 0.08 && p.Y > 0 && p.Z > 0 && p.Z < 0.04, $"particle {i} at {p} left the tank");
        }

        Assert.True(fluid.Densities.ToArray().Max() < 1.03 * fluid.RestDensity, $"largest density {fluid.Densities.ToArray().Max()}");
    }
}
