using System;
using System.Collections.Generic;
using ParticlePhysics.Cloth;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using Xunit.Abstractions;

namespace ParticlePhysics.Tests.Cloth;

/// <summary>
/// The constant-strain triangle membrane against exact solutions: the patch test (a uniform strain on any triangulation
/// gives the exact stress, rigid motions no force), its Jacobian against finite differences, and a strip pulled at one
/// end, which stretches by F / (Y b) per unit length under xpbd and under implicit Euler.
/// </summary>
public class MembraneTests
{
    private readonly ITestOutputHelper _output;

    public MembraneTests(ITestOutputHelper output)
    {
        _output = output;
    }

    [Theory]
    [InlineData(0.0, 1)]
    [InlineData(0.3, 2)]
    [InlineData(0.45, 3)]
    public void A_uniform_strain_on_a_random_triangulation_gives_the_exact_stress(double nu, int seed)
    {
        const double Y = 700.0;
        var (vertices, triangles) = ClothMeshes.RandomSquare(6, seed);
        var (world, membrane) = Membrane(vertices, triangles, Y, nu);

        // x = G X with G stretching, shearing and lifting the plane: a uniform Green strain.
        double[,] g = { { 1.03, 0.02, -0.01 }, { 0.01, 0.98, 0.04 }, { 0.005, 0.03, 1.05 } };
        var n = world.Count;
        for (var i = 0; i < n; i++)
        {
            var p = world.GetPosition(i);
            world.SetPosition(i, new Vector3d(
                (g[0, 0] * p.X) + (g[0, 1] * p.Y) + (g[0, 2] * p.Z),
                (g[1, 0] * p.X) + (g[1, 1] * p.Y) + (g[1, 2] * p.Z),
                (g[2, 0] * p.X) + (g[2, 1] * p.Y) + (g[2, 2] * p.Z)));
        }

        // The plane's rest axes are x and z: F = [G e_x, G e_z], E = (F^T F - I) / 2, S = 2 mu E + lambda tr E I, P = F S.
        var f1 = new Vector3d(g[0, 0], g[1, 0], g[2, 0]);
        var f2 = new Vector3d(g[0, 2], g[1, 2], g[2, 2]);
        double exx = 0.5 * (f1.LengthSquared - 1), ezz = 0.5 * (f2.LengthSquared - 1), exz = 0.5 * Vector3d.Dot(f1, f2);
        double mu = Y / (2 * (1 + nu)), lambda = Y * nu / (1 - (nu * nu));
        double sxx = (2 * mu * exx) + (lambda * (exx + ezz)), szz = (2 * mu * ezz) + (lambda * (exx + ezz)), sxz = 2 * mu * exz;
        Vector3d Traction(double nx, double nz) => (f1 * ((sxx * nx) + (sxz * nz))) + (f2 * ((sxz * nx) + (szz * nz)));

        var forces = new double[3 * n];
        membrane.AddForces(world.View(), forces);
        var energy = membrane.PotentialEnergy(world.View());
        var exact = (mu * ((exx * exx) + (ezz * ezz) + (2 * exz * exz))) + (0.5 * lambda * (exx + ezz) * (exx + ezz));
        Assert.Equal(exact, energy, 1e-12 * Y);

        // Each node: the traction of the exact stress over half of each boundary edge it ends; inner nodes nothing.
        var side = 7;
        var h = 1.0 / 6;
        var worst = 0.0;
        for (var i = 0; i < n; i++)
        {
            int row = i / side, col = i % side;
            var expected = Vector3d.Zero;
            if (row == 0)
            {
                expected += -0.5 * h * (col == 0 || col == side - 1 ? 1 : 2) * Traction(-1, 0);
            }

            if (row == side - 1)
            {
                expected += -0.5 * h * (col == 0 || col == side - 1 ? 1 : 2) * Traction(1, 0);
            }

            if (col == 0)
            {
                expected += -0.5 * h * (row == 0 || row == side - 1 ? 1 : 2) * Traction(0, -1);
            }

            if (col == side - 1)
            {
                expected += -0.5 * h * (row == 0 || row == side - 1 ? 1 : 2) * Traction(0, 1);
            }

            var actual = new Vector3d(forces[3 * i], forces[(3 * i) + 1], forces[(3 * i) + 2]);
            worst = Math.Max(worst, (actual - expected).Length);
        }

        Assert.True(worst < 1e-12 * Y, $"nodal forces differ from the exact stress's by up to {worst:G3} N");
    }

    [Fact]
    public void Rigid_motions_give_no_force_and_no_energy()
    {
        var (vertices, triangles) = ClothMeshes.RandomSquare(5, 4);
        var (world, membrane) = Membrane(vertices, triangles, 1000, 0.3);
        var rotation = global::ParticlePhysics.Constraints.Rotation3d.FromAxisAngle(new Vector3d(1, 2, 3), 0.7);
        for (var i = 0; i < world.Count; i++)
        {
            world.SetPosition(i, rotation.Rotate(world.GetPosition(i)) + new Vector3d(3, -2, 5));
        }

        var forces = new double[3 * world.Count];
        membrane.AddForces(world.View(), forces);
        foreach (var f in forces)
        {
            Assert.True(Math.Abs(f) < 1e-10, $"force {f} N under a rigid motion");
        }

        Assert.True(Math.Abs(membrane.PotentialEnergy(world.View())) < 1e-12);
    }

    [Fact]
    public void The_jacobian_matches_finite_differences_of_the_forces_under_tension()
    {
        var (vertices, triangles) = ClothMeshes.RandomSquare(3, 9);
        var (world, membrane) = Membrane(vertices, triangles, 500, 0.3, damping: 2.0);
        var random = new Random(5);
        var n = world.Count;

        // Stretched 8 % both ways (both principal stresses positive, so S+ = S and J is the exact df/dx), and jiggled.
        for (var i = 0; i < n; i++)
        {
            var p = world.GetPosition(i);
            world.SetPosition(i, new Vector3d(1.08 * p.X, 0.01 * random.NextDouble(), 1.08 * p.Z));
        }

        var x = world.Positions.ToArray();
        var zero = new double[3 * n];
        var w = new double[3 * n];
        for (var k = 0; k < w.Length; k++)
        {
            w[k] = (2 * random.NextDouble()) - 1;
        }

        // df/dx w by central differences at rest velocities, against J with a = 1, b = 0.
        var step = 1e-6;
        var plus = Forces(membrane, world, Shift(x, w, step), zero);
        var minus = Forces(membrane, world, Shift(x, w, -step), zero);
        var product = new double[3 * n];
        membrane.Linearize(State(world, x, zero), 1.0, 0.0, new double[3 * n]);
        membrane.AddJacobianProduct(w, product);
        for (var k = 0; k < product.Length; k++)
        {
            Assert.Equal((plus[k] - minus[k]) / (2 * step), product[k], 1e-4);
        }

        // df/dv w: the damping is linear in the velocities.
        var atW = Forces(membrane, world, x, w);
        var atZero = Forces(membrane, world, x, zero);
        Array.Clear(product);
        membrane.Linearize(State(world, x, zero), 0.0, 1.0, new double[3 * n]);
        membrane.AddJacobianProduct(w, product);
        for (var k = 0; k < product.Length; k++)
        {
            Assert.Equal(atW[k] - atZero[k], product[k], 1e-9);
        }

        // The diagonal and coupling blocks are the product's: J e_j, column by column.
        membrane.Linearize(State(world, x, zero), 0.7, 0.3, new double[3 * n]);
        var dense = new double[3 * n, 3 * n];
        for (var j = 0; j < 3 * n; j++)
        {
            var unit = new double[3 * n];
            unit[j] = 1;
            var column = new double[3 * n];
            membrane.AddJacobianProduct(unit, column);
            for (var k = 0; k < 3 * n; k++)
            {
                dense[k, j] = column[k];
                Assert.Equal(column[k], dense[k, j]);
            }
        }

        var diagonal = new double[9 * n];
        membrane.AddDiagonalBlocks(diagonal);
        var pairs = membrane.CouplingCount;
        var first = new int[pairs];
        var second = new int[pairs];
        membrane.WriteCouplings(first, second);
        var blocks = new double[9 * 2 * pairs];
        var forward = new int[pairs];
        var backward = new int[pairs];
        for (var c = 0; c < pairs; c++)
        {
            forward[c] = 2 * c;
            backward[c] = (2 * c) + 1;
        }

        membrane.AddCouplingBlocks(blocks, forward, backward);
        var assembled = new double[3 * n, 3 * n];
        for (var i = 0; i < n; i++)
        {
            for (var r = 0; r < 9; r++)
            {
                assembled[(3 * i) + (r / 3), (3 * i) + (r % 3)] += diagonal[(9 * i) + r];
            }
        }

        for (var c = 0; c < pairs; c++)
        {
            for (var r = 0; r < 9; r++)
            {
                assembled[(3 * first[c]) + (r / 3), (3 * second[c]) + (r % 3)] += blocks[(18 * c) + r];
                assembled[(3 * second[c]) + (r / 3), (3 * first[c]) + (r % 3)] += blocks[(18 * c) + 9 + r];
            }
        }

        for (var r = 0; r < 3 * n; r++)
        {
            for (var c = 0; c < 3 * n; c++)
            {
                Assert.Equal(dense[r, c], assembled[r, c], 1e-9);
                Assert.Equal(dense[r, c], dense[c, r], 1e-9);
            }
        }
    }

    [Theory]
    [InlineData("implicit-euler")]
    [InlineData("xpbd")]
    public void A_strip_pulled_at_one_end_stretches_by_F_over_Y_b(string integrator)
    {
        var (strain, exact) = PulledStrip(integrator, 0.0, 20, 1.0);
        _output.WriteLine($"{integrator}, nu = 0: strain {strain:G6}, F / (Y b) = {exact:G6}, error {((strain / exact) - 1) * 100:F3} %");
        Assert.True(Math.Abs((strain / exact) - 1) < 0.02, $"strain {strain} against {exact}");
    }

    [Theory]
    [InlineData("implicit-euler")]
    [InlineData("xpbd")]
    public void The_middle_half_of_a_long_strip_with_poisson_0_3_stretches_by_F_over_Y_b(string integrator)
    {
        var (strain, exact) = PulledStrip(integrator, 0.3, 40, 2.0);
        _output.WriteLine($"{integrator}, nu = 0.3: strain {strain:G6}, F / (Y b) = {exact:G6}, error {((strain / exact) - 1) * 100:F3} %");
        Assert.True(Math.Abs((strain / exact) - 1) < 0.02, $"strain {strain} against {exact}");
    }

    /// <summary>
    /// A strip of width b = 0.2 m and length <paramref name="length"/> (n x 4 cells), pinned along x = 0 and pulled along
    /// +x by F = Y b / 1000 at x = L in nodal shares (half at the corners); stepped with drag until at rest. Returns the
    /// stretch per unit length (of the whole strip for nu = 0, of its middle half otherwise) and F / (Y b). Under xpbd
    /// one Gauss-Seidel sweep per substep leaves a static bias of order (h c / dx)^2 (c the speed of sound): at
    /// 1000 N/m, 100 kg/m^2 and 20 substeps of 1/60 s it is below 0.1 %.
    /// </summary>
    private static (double Strain, double Exact) PulledStrip(string integrator, double nu, int n, double length)
    {
        const int m = 4;
        const double Y = 1000, b = 0.2;
        var force = Y * b / 1000;
        var (vertices, triangles) = ClothMeshes.Strip(n, m, length / n, b / m);
        var builder = new MeshClothBuilder(new WeldedMesh(vertices, triangles))
        {
            Modulus = Y,
            Poisson = nu,
            MembraneDamping = 0,
            AreaDensity = 100,
            Drag = 2.5,
            Gravity = 0,
        };
        for (var j = 0; j <= m; j++)
        {
            builder.Pin(j);
        }

        var cloth = builder.Build();
        var loads = new NodalLoads();
        for (var j = 0; j <= m; j++)
        {
            loads.Loads.Add((cloth.ParticleIndex((n * (m + 1)) + j), new Vector3d(force / m * (j == 0 || j == m ? 0.5 : 1), 0, 0)));
        }

        cloth.System.AddForce(loads);
        var stepper = integrator == "xpbd" ? (IIntegrator)new Xpbd(20) : new ImplicitEuler { Tolerance = 1e-10 };
        for (var s = 0; s < 600; s++)
        {
            cloth.System.Step(stepper, 1.0 / 60);
        }

        double MeanX(int row)
        {
            var sum = 0.0;
            for (var j = 0; j <= m; j++)
            {
                sum += cloth.System.GetPosition(cloth.ParticleIndex((row * (m + 1)) + j)).X;
            }

            return sum / (m + 1);
        }

        int first = nu == 0 ? 0 : n / 4, last = nu == 0 ? n : 3 * n / 4;
        var strain = ((MeanX(last) - MeanX(first)) / ((last - first) * length / n)) - 1;
        return (strain, force / (Y * b));
    }

    private static (ParticleWorld World, TriangleMembrane Membrane) Membrane(double[] vertices, int[] triangles, double modulus, double nu, double damping = 0)
    {
        var mesh = new WeldedMesh(vertices, triangles);
        var world = new ParticleWorld();
        for (var i = 0; i < mesh.ParticleCount; i++)
        {
            world.AddParticle(mesh.ParticlePosition(i), 1);
        }

        var membrane = new TriangleMembrane(world);
        for (var t = 0; t < mesh.TriangleCount; t++)
        {
            var c = mesh.ParticleTriangles;
            membrane.Add(c[3 * t], c[(3 * t) + 1], c[(3 * t) + 2], modulus, nu, damping);
        }

        return (world, membrane);
    }

    private static double[] Shift(double[] x, double[] w, double step)
    {
        var result = (double[])x.Clone();
        for (var k = 0; k < x.Length; k++)
        {
            result[k] += step * w[k];
        }

        return result;
    }

    private static ParticleState State(ParticleWorld world, double[] x, double[] v) =>
        new(0, x, v, world.Masses, world.InverseMasses);

    private static double[] Forces(TriangleMembrane membrane, ParticleWorld world, double[] x, double[] v)
    {
        var forces = new double[x.Length];
        membrane.AddForces(State(world, x, v), forces);
        return forces;
    }
}
