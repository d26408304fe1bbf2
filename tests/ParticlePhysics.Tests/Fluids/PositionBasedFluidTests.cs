using System;
using ParticlePhysics.Contacts;
using ParticlePhysics.Fluids;
using Xunit;

namespace ParticlePhysics.Tests.Fluids;

/// <summary>
/// The density projection of <see cref="PositionBasedFluid"/>: the rest lattice is at the rest density, a compressed
/// block is pushed back towards it, and every projection and velocity pass keeps the momentum of its particles.
/// </summary>
public class PositionBasedFluidTests
{
    private const double Spacing = 0.01;

    [Fact]
    public void A_block_at_rest_on_its_lattice_is_not_moved_by_its_density_constraints()
    {
        var (world, fluid) = Block(Spacing);
        var before = world.Positions.ToArray();
        Substep(world, fluid, 1.0 / 600, velocities: false);

        // The interior is at rho_0 (kappa), the faces below it: nothing is compressed, so nothing moves beyond rounding.
        var after = world.Positions.ToArray();
        for (var k = 0; k < before.Length; k++)
        {
            Assert.Equal(before[k], after[k], 14);
        }

        Assert.True(fluid.PairCount > 13 * world.Count / 2, $"{fluid.PairCount} neighbour pairs for {world.Count} particles");
    }

    [Fact]
    public void A_block_cut_from_the_walls_of_its_box_is_at_the_rest_density_against_them_corners_included()
    {
        // The block fills [0, 6 s]^3 against five planes (floor and four sides): every particle but those of the top
        // layer, which has no fluid above, has its missing neighbours beyond the walls as ghosts, counted once where
        // two or three walls meet.
        var (world, fluid) = Block(Spacing, origin: new Vector3d(0.5 * Spacing, 0.5 * Spacing, 0.5 * Spacing));
        fluid.Boundary = Box(6 * Spacing);
        var before = world.Positions.ToArray();
        Substep(world, fluid, 1.0 / 600, velocities: false);

        var densities = fluid.Densities;
        var particles = fluid.Particles;
        for (var k = 0; k < fluid.Count; k++)
        {
            var top = world.GetPosition(particles[k]).Y > 5 * Spacing;
            if (top)
            {
                Assert.True(densities[k] < 0.95 * 1000, $"a particle of the top layer has {densities[k]} kg/m^3");
            }
            else
            {
                Assert.Equal(1000.0, densities[k], 9);
            }
        }

        var after = world.Positions.ToArray();
        for (var k = 0; k < before.Length; k++)
        {
            Assert.Equal(before[k], after[k], 14);
        }

        Assert.True(fluid.WallCount > 0);
    }

    [Fact]
    public void A_block_pressed_into_the_floor_is_pushed_back_out_of_it()
    {
        // A quarter of a spacing lower than its rest place, the bottom layer is a quarter of a spacing from the floor,
        // not half: the floor's ghosts compress it, and the projection lifts the block, the floor taking the reaction.
        var (world, fluid) = Block(Spacing, origin: new Vector3d(0.5 * Spacing, 0.25 * Spacing, 0.5 * Spacing));
        var contacts = new ContactSet();
        contacts.Add(FluidTank.Floor());
        fluid.Boundary = contacts;
        var before = world.TotalMomentum();
        var lift = -Momentum(world);
        Substep(world, fluid, 1.0 / 600, velocities: false);

        lift += Momentum(world);
        Assert.True(fluid.Densities[74] > 1000.0, $"the middle of the bottom layer is at {fluid.Densities[74]} kg/m^3 before the move");
        Assert.True(lift.Y > 1e-6 * fluid.ParticleMass * Spacing, $"the block's sum of m dy is {lift.Y:G3} kg m");
        Assert.Equal(0.0, lift.X, 15);
        Assert.Equal(0.0, lift.Z, 15);
        Assert.Equal(before, world.TotalMomentum());
    }

    [Fact]
    public void A_compressed_block_is_pushed_back_towards_the_rest_density_and_keeps_its_momentum_exactly()
    {
        var (world, fluid) = Block(0.8 * Spacing, spacing: Spacing);
        var momentum = Momentum(world);
        var start = MaxDensityError(world, fluid);
        for (var iteration = 0; iteration < 20; iteration++)
        {
            Substep(world, fluid, 1.0 / 600);
        }

        var end = MaxDensityError(world, fluid);
        Assert.True(start > 0.5, $"the block at 0.8 s starts {start:P1} compressed");
        Assert.True(end < 0.3 * start, $"the largest compression went from {start:P1} to {end:P1}");
        var moved = Momentum(world);
        Assert.Equal(momentum.X, moved.X, 12);
        Assert.Equal(momentum.Y, moved.Y, 12);
        Assert.Equal(momentum.Z, moved.Z, 12);
    }

    [Fact]
    public void Xsph_viscosity_keeps_the_momentum_and_evens_out_the_velocities()
    {
        var (world, fluid) = Block(Spacing);
        fluid.Viscosity = 0.5;
        var random = new Random(3);
        for (var i = 0; i < world.Count; i++)
        {
            world.SetVelocity(i, new Vector3d(random.NextDouble() - 0.5, random.NextDouble() - 0.5, random.NextDouble() - 0.5));
        }

        var momentum = world.TotalMomentum();
        var energy = world.KineticEnergy();
        Substep(world, fluid, 1.0 / 60);
        var after = world.TotalMomentum();
        Assert.Equal(momentum.X, after.X, 12);
        Assert.Equal(momentum.Y, after.Y, 12);
        Assert.Equal(momentum.Z, after.Z, 12);
        Assert.True(world.KineticEnergy() < 0.8 * energy, $"kinetic energy {energy:G4} J became {world.KineticEnergy():G4} J");
    }

    [Theory]
    [InlineData(1.0)]
    [InlineData(-1.0)]
    public void Vorticity_confinement_spins_a_vortex_up_in_its_own_sense(double sense)
    {
        // A vortex about the block's vertical axis, v = Omega(r) z x r with Omega = Omega_0 / (1 + r^2 / R^2): |omega|
        // peaks on the axis, so N points inwards and N x omega runs along the flow, whichever way it turns; the
        // angular momentum about the axis grows, and without confinement the velocity pass leaves it as it is.
        foreach (var vorticity in new[] { 0.0, 0.5 })
        {
            var (world, fluid) = Block(Spacing);
            fluid.Vorticity = vorticity;
            var axis = new Vector3d(2.5 * Spacing, 0.0, 2.5 * Spacing);
            for (var i = 0; i < world.Count; i++)
            {
                var r = world.GetPosition(i) - axis;
                var spin = sense * 2.0 / (1.0 + ((r.X * r.X) + (r.Z * r.Z)) / (2.25 * Spacing * Spacing));
                world.SetVelocity(i, new Vector3d(spin * r.Z, 0.0, -spin * r.X));
            }

            var before = AngularMomentum(world, axis);
            Substep(world, fluid, 1.0 / 60);
            var after = AngularMomentum(world, axis);
            if (vorticity == 0.0)
            {
                Assert.Equal(before, after, 15);
            }
            else
            {
                Assert.True(sense * (after - before) > 0.001 * Math.Abs(before), $"the angular momentum went from {before:G4} to {after:G4} kg m^2/s");
            }
        }
    }

    [Fact]
    public void Bad_parameters_are_refused_with_their_value()
    {
        var world = new ParticleWorld();
        Assert.Throws<ArgumentOutOfRangeException>(() => new PositionBasedFluid(world, 0.0, 1000));
        Assert.Throws<ArgumentOutOfRangeException>(() => new PositionBasedFluid(world, 0.01, -1));
        var fluid = new PositionBasedFluid(world, 0.01, 1000);
        var error = Assert.Throws<ArgumentOutOfRangeException>(() => fluid.Viscosity = 1.5);
        Assert.Contains("1.5", error.Message);
        Assert.Throws<ArgumentOutOfRangeException>(() => fluid.Relaxation = -1);
        Assert.Throws<ArgumentOutOfRangeException>(() => fluid.Iterations = 0);
        var p = world.AddParticle(Vector3d.Zero, 1e-3);
        fluid.Add(new[] { p });
        Assert.Throws<ArgumentException>(() => fluid.Add(new[] { p }));
        Assert.Throws<ArgumentOutOfRangeException>(() => fluid.Add(new[] { 7 }));
        var q = world.AddParticle(new Vector3d(1, 0, 0), 1e-3);
        Assert.Contains($"Particle {q} is listed twice (at 0 and 1)", Assert.Throws<ArgumentException>(() => fluid.Add(new[] { q, q })).Message);
        Assert.False(fluid.IsFluid(q));
        fluid.Add(new[] { q });
        Assert.True(fluid.IsFluid(q));
        Assert.Equal(2, fluid.Count);
    }

    // A 6 x 6 x 6 block at pitch `pitch` from `origin` of particles of the fluid of spacing `spacing` (mass rho_0 s^3).
    private static (ParticleWorld World, PositionBasedFluid Fluid) Block(double pitch, double? spacing = null, Vector3d origin = default)
    {
        var world = new ParticleWorld();
        var fluid = new PositionBasedFluid(world, spacing ?? pitch, 1000);
        var indices = new int[216];
        for (var k = 0; k < indices.Length; k++)
        {
            indices[k] = world.AddParticle(origin + new Vector3d(pitch * (k % 6), pitch * (k / 6 % 6), pitch * (k / 36)), fluid.ParticleMass);
        }

        fluid.Add(indices);
        return (world, fluid);
    }

    // A box of five planes (no lid) over [0, size] on x and z, the floor at y = 0.
    private static ContactSet Box(double size)
    {
        var contacts = new ContactSet();
        contacts.Add(FluidTank.Floor());
        foreach (var side in FluidTank.Sides(size, size))
        {
            contacts.Add(side);
        }

        return contacts;
    }

    // The angular momentum about the vertical line through `axis`, sum m (r_z v_x - r_x v_z) (y up).
    private static double AngularMomentum(ParticleWorld world, Vector3d axis)
    {
        var sum = 0.0;
        for (var i = 0; i < world.Count; i++)
        {
            var r = world.GetPosition(i) - axis;
            var v = world.GetVelocity(i);
            sum += world.GetMass(i) * ((r.Z * v.X) - (r.X * v.Z));
        }

        return sum;
    }

    private static Vector3d Momentum(ParticleWorld world)
    {
        var sum = Vector3d.Zero;
        for (var i = 0; i < world.Count; i++)
        {
            sum += world.GetMass(i) * world.GetPosition(i);
        }

        return sum;
    }

    // The largest rho / rho_0 - 1, summed over every pair with the kernel and normalised by the rest lattice's sum (the fluid's kappa), apart from the set.
    private static double MaxDensityError(ParticleWorld world, PositionBasedFluid fluid)
    {
        var max = 0.0;
        var kernel = new SphKernel(fluid.SmoothingRadius);
        var rest = 0.0;
        for (int z = -2; z <= 2; z++)
        {
            for (int y = -2; y <= 2; y++)
            {
                for (int x = -2; x <= 2; x++)
                {
                    rest += kernel.Density(fluid.Spacing * Math.Sqrt((x * x) + (y * y) + (z * z)));
                }
            }
        }

        for (var i = 0; i < world.Count; i++)
        {
            var sum = 0.0;
            for (var j = 0; j < world.Count; j++)
            {
                sum += kernel.Density((world.GetPosition(i) - world.GetPosition(j)).Length);
            }

            max = Math.Max(max, (sum / rest) - 1.0);
        }

        return max;
    }

    // One substep of the set alone on the world's state (its projection, then its velocity pass if asked), written back.
    private static void Substep(ParticleWorld world, PositionBasedFluid fluid, double dt, bool velocities = true)
    {
        var n = 3 * world.Count;
        var state = new double[2 * n];
        world.Positions.CopyTo(state);
        world.Velocities.CopyTo(state.AsSpan(n));
        var start = (double[])state.Clone();
        var context = new ConstraintContext(
            0.0, dt, start.AsSpan(0, n), start.AsSpan(n), state.AsSpan(0, n), state.AsSpan(n), world.Masses, world.InverseMasses, world.Radii);
        fluid.Project(in context);
        if (velocities)
        {
            fluid.SolveVelocities(in context);
        }

        world.SetState(state);
    }
}
