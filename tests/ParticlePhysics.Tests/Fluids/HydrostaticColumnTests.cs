using System;
using ParticlePhysics.Contacts;
using ParticlePhysics.Integrators;
using Xunit;
using Xunit.Abstractions;

namespace ParticlePhysics.Tests.Fluids;

/// <summary>
/// Water at rest in a closed box (the exact solution: it stays as it is, at its rest density, its pressure rising
/// with depth): a column 0.3 m deep at 1 cm spacing, stepped at 60 Hz for 10 s.
/// </summary>
public class HydrostaticColumnTests
{
    private const double Spacing = 0.01;
    private const double Width = 0.1;
    private const double Depth = 0.3;

    private readonly ITestOutputHelper _output;

    public HydrostaticColumnTests(ITestOutputHelper output) => _output = output;

    [Fact]
    [Trait("Category", "Long")]
    public void A_column_of_water_in_a_closed_box_stays_at_its_height_and_density_and_comes_to_rest()
    {
        var floor = new BoxObstacle(new Vector3d(0.5 * Width, -0.05, 0.5 * Width), new Vector3d(0.1, 0.05, 0.1));
        var lid = new BoxObstacle(new Vector3d(0.5 * Width, 0.45, 0.5 * Width), new Vector3d(0.1, 0.05, 0.1));
        var sides = FluidTank.Sides(Width, Width);
        var (world, fluid) = FluidTank.Fill(Spacing, Vector3d.Zero, new Vector3d(Width, Depth, Width), floor, lid, sides[0], sides[1], sides[2], sides[3]);
        var top = Top(world);
        var mass = 0.0;
        for (var i = 0; i < world.Count; i++)
        {
            mass += world.GetMass(i);
        }

        var xpbd = new Xpbd(40);
        for (var step = 0; step < 600; step++)
        {
            world.Step(xpbd, 1.0 / 60);
        }

        // The top: the mean height of the highest layer's worth of particles, plus half a spacing, against 0.3 m.
        var height = Top(world);
        _output.WriteLine($"top {top:F4} m -> {height:F4} m ({(height / top) - 1.0:+0.00%;-0.00%})");
        Assert.True(Math.Abs((height / top) - 1.0) < 0.02, $"the top went from {top:F4} m to {height:F4} m");
        var positions = world.Positions;
        for (var i = 0; i < world.Count; i++)
        {
            double x = positions[3 * i], y = positions[(3 * i) + 1], z = positions[(3 * i) + 2];
            Assert.True(x > 0 && x < Width && y > 0 && y < 0.4 && z > 0 && z < Width, $"particle {i} is at ({x}, {y}, {z}), out of the box");
        }

        var speed = world.TotalMomentum().Length / mass;
        _output.WriteLine($"centre of mass speed {speed:G3} m/s");
        Assert.True(speed < 0.01, $"the centre of mass moves at {speed:G3} m/s");
        double mean = 0.0, largest = 0.0;
        foreach (var density in fluid.Densities)
        {
            var error = Math.Max((density / fluid.RestDensity) - 1.0, 0.0);
            mean += error / fluid.Count;
            largest = Math.Max(largest, error);
        }

        _output.WriteLine($"density error: mean {mean:P3}, largest {largest:P3}");

        // The error of the constraint, rho / rho_0 - 1 where the water is compressed: the top layer, with no water
        // above it, is below rho_0 by the missing neighbours, not by a rarefaction.
        Assert.True(mean < 0.01, $"the mean density error is {mean:P2}");
        Assert.True(largest < 0.03, $"the largest density error is {largest:P2}");
    }

    private static double Top(ParticleWorld world)
    {
        var heights = new double[world.Count];
        for (var i = 0; i < world.Count; i++)
        {
            heights[i] = world.GetPosition(i).Y;
        }

        Array.Sort(heights);
        var layer = (int)Math.Round(Width / Spacing * (Width / Spacing));
        var sum = 0.0;
        for (var k = heights.Length - layer; k < heights.Length; k++)
        {
            sum += heights[k];
        }

        return (sum / layer) + (0.5 * Spacing);
    }
}
