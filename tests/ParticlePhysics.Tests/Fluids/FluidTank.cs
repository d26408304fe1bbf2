using ParticlePhysics.Contacts;
using ParticlePhysics.Fluids;
using ParticlePhysics.Forces;

namespace ParticlePhysics.Tests.Fluids;

/// <summary>Water in a tank for the fluid's tests: a block of fluid under gravity among walls that bound it.</summary>
internal static class FluidTank
{
    /// <summary>
    /// A world under 9.81 m/s^2 of gravity holding water (1000 kg/m^3) filling [min, max] at <paramref name="spacing"/>,
    /// and a contact set of <paramref name="walls"/> added after it, which is the fluid's boundary.
    /// </summary>
    public static (ParticleWorld World, PositionBasedFluid Fluid) Fill(double spacing, Vector3d min, Vector3d max, params Obstacle[] walls)
    {
        var world = new ParticleWorld();
        world.AddForce(Gravity.Down(9.81));
        var fluid = new PositionBasedFluid(world, spacing, 1000);
        fluid.AddBox(min, max);
        var contacts = new ContactSet { PairFilter = fluid.PairFilter };
        foreach (var wall in walls)
        {
            contacts.Add(wall);
        }

        fluid.Boundary = contacts;
        world.AddConstraints(fluid);
        world.AddConstraints(contacts);
        return (world, fluid);
    }

    /// <summary>The four upright sides of a tank over [0, width] on x and [0, depth] on z.</summary>
    public static Obstacle[] Sides(double width, double depth) => new Obstacle[]
    {
        new PlaneObstacle(Vector3d.Zero, new Vector3d(1, 0, 0)),
        new PlaneObstacle(new Vector3d(width, 0, 0), new Vector3d(-1, 0, 0)),
        new PlaneObstacle(Vector3d.Zero, new Vector3d(0, 0, 1)),
        new PlaneObstacle(new Vector3d(0, 0, depth), new Vector3d(0, 0, -1)),
    };

    /// <summary>The floor y = 0.</summary>
    public static Obstacle Floor() => new PlaneObstacle(Vector3d.Zero, new Vector3d(0, 1, 0));
}
