using System;
using ParticlePhysics.Cloth;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using Xunit.Abstractions;

namespace ParticlePhysics.Tests.Cloth;

/// <summary>
/// Plate bending (<see cref="PlateBending"/>) against Kirchhoff plate theory: no energy for rigid motions of a flat
/// sheet, D A / (2 R^2) for a cylinder, and a cantilever strip's sag rho_A g L^4 / (8 D), converging as the mesh is
/// refined on a regular and on a randomly perturbed triangulation.
/// </summary>
public class PlateBendingTests
{
    private const double Rigidity = 24.5; // N m
    private const double Density = 0.1; // kg/m^2
    private const double G = 9.81;

    private readonly ITestOutputHelper _output;

    public PlateBendingTests(ITestOutputHelper output)
    {
        _output = output;
    }

    [Fact]
    public void Rigid_motions_and_in_plane_stretches_of_a_flat_sheet_cost_no_energy()
    {
        var (vertices, triangles) = ClothMeshes.RandomSquare(8, 3);
        var (world, bending) = Sheet(vertices, triangles, 2.0);
        var rotation = global::ParticlePhysics.Constraints.Rotation3d.FromAxisAngle(new Vector3d(-1, 2, 0.5), 1.1);
        for (var i = 0; i < world.Count; i++)
        {
            var p = world.GetPosition(i);
            world.SetPosition(i, rotation.Rotate(new Vector3d(1.3 * p.X, 0, (0.8 * p.Z) + (0.2 * p.X))) + new Vector3d(4, 1, -2));
        }

        var energy = bending.PotentialEnergy(world.View());
        var forces = new double[3 * world.Count];
        bending.AddForces(world.View(), forces);
        Assert.True(Math.Abs(energy) < 1e-10, $"energy {energy} J");
        Assert.All(forces, f => Assert.True(Math.Abs(f) < 1e-9, $"force {f} N"));
    }

    [Theory]
    [InlineData(0.0)]
    [InlineData(0.25)]
    public void A_sheet_bent_into_a_cylinder_has_energy_D_A_over_2_R_squared(double jitter)
    {
        const double radius = 0.8;
        var errors = new double[3];
        var sizes = new[] { 10, 20, 40 };
        for (var k = 0; k < sizes.Length; k++)
        {
            var n = sizes[k];
            var (vertices, triangles) = ClothMeshes.Strip(n, n, 1.0 / n, 1.0 / n, jitter: jitter, seed: n);
            var (world, bending) = Sheet(vertices, triangles, Rigidity);
            for (var i = 0; i < world.Count; i++)
            {
                var p = world.GetPosition(i);
                world.SetPosition(i, new Vector3d(radius * Math.Sin(p.X / radius), radius * (1 - Math.Cos(p.X / radius)), p.Z));
            }

            var exact = Rigidity * Area(vertices, triangles) / (2 * radius * radius);
            errors[k] = (bending.PotentialEnergy(world.View()) / exact) - 1;
            _output.WriteLine($"jitter {jitter}, {n} x {n}: energy error {errors[k] * 100:F3} %");
        }

        Assert.True(Math.Abs(errors[2]) < 0.05, $"error {errors[2]:P2} at 40 x 40");
        Assert.True(Math.Abs(errors[2]) < Math.Abs(errors[0]), "the energy does not converge");
    }

    [Theory]
    [InlineData(0.0)]
    [InlineData(0.25)]
    public void A_cantilever_strip_sags_rho_g_L4_over_8_D_and_converges(double jitter)
    {
        var sizes = new[] { 10, 20, 40 };
        var errors = new double[sizes.Length];
        for (var k = 0; k < sizes.Length; k++)
        {
            var (builder, n, m) = Cantilever(sizes[k], jitter);
            var pinned = new bool[builder.Mesh.ParticleCount];
            for (var i = 0; i < 2 * (m + 1); i++)
            {
                pinned[i] = true;
            }

            var world = new ParticleWorld();
            for (var i = 0; i < builder.Mesh.ParticleCount; i++)
            {
                world.AddParticle(builder.Mesh.ParticlePosition(i), 1);
            }

            var bending = new QuadraticBending(world);
            PlateBending.AddSheet(bending, builder.Mesh.ParticleTriangles, builder.Mesh.ParticlePositions, 0, Rigidity);
            var w = ClothMeshes.StaticDeflection(bending, builder.ParticleMasses(), pinned, G);
            errors[k] = (FreeEdge(w, n, m) / Sag()) - 1;
            _output.WriteLine($"jitter {jitter}, {sizes[k]} segments: sag error {errors[k] * 100:F3} %");
        }

        Assert.True(Math.Abs(errors[1]) < 0.05, $"error {errors[1]:P2} at 20 segments");
        Assert.True(Math.Abs(errors[2]) < 0.05, $"error {errors[2]:P2} at 40 segments");
        if (jitter == 0)
        {
            // Second order on the regular grid: each halving of the spacing divides the error by about 4.
            Assert.InRange(Math.Log2(errors[0] / errors[1]), 1.8, 2.2);
            Assert.InRange(Math.Log2(errors[1] / errors[2]), 1.8, 2.2);
        }
        else
        {
            // On the perturbed mesh the error is the perturbation's as much as the spacing's, but it still falls.
            Assert.True(Math.Abs(errors[2]) < Math.Abs(errors[0]), $"the sag does not converge: {errors[0]:P2} at 10, {errors[2]:P2} at 40 segments");
        }
    }

    [Fact]
    public void A_cantilever_cloth_stepped_to_rest_by_implicit_euler_sags_as_the_static_solution()
    {
        var (builder, n, m) = Cantilever(20, 0.0);
        var cloth = builder.Build();
        var stepper = new ImplicitEuler { Tolerance = 1e-9 };
        for (var s = 0; s < 40; s++)
        {
            cloth.System.Step(stepper, 0.1);
        }

        var y = new double[cloth.ParticleCount];
        for (var i = 0; i < y.Length; i++)
        {
            y[i] = cloth.System.GetPosition(cloth.FirstParticle + i).Y;
        }

        var error = (FreeEdge(y, n, m) / Sag()) - 1;
        _output.WriteLine($"implicit Euler, membrane Y = 1e5 N/m and D = {Rigidity} N m, 20 segments: sag error {error * 100:F3} %");
        Assert.True(Math.Abs(error) < 0.01, $"error {error:P2}");
    }

    /// <summary>rho_A g L^4 / (8 D), downwards, for L = 1 m.</summary>
    private static double Sag() => -Density * G / (8 * Rigidity);

    /// <summary>
    /// A strip of n segments along x (rows at (i - 1/2) h, h = L / (n - 1/2), so that L = 1 m from midway between the
    /// two pinned rows 0 and 1 to the free edge) and m = n / 5 across, the first two rows pinned.
    /// </summary>
    private static (MeshClothBuilder Builder, int N, int M) Cantilever(int n, double jitter)
    {
        var m = Math.Max(2, n / 5);
        var h = 1.0 / (n - 0.5);
        var (vertices, triangles) = ClothMeshes.Strip(n, m, h, h, x0: -0.5 * h, jitter: jitter, seed: 7);
        var builder = new MeshClothBuilder(new WeldedMesh(vertices, triangles))
        {
            Modulus = 1e5,
            Poisson = 0,
            MembraneDamping = 0,
            AreaDensity = Density,
            BendingRigidity = Rigidity,
            Drag = 0.01,
        };
        for (var i = 0; i < 2 * (m + 1); i++)
        {
            builder.Pin(i);
        }

        return (builder, n, m);
    }

    private static double FreeEdge(double[] w, int n, int m)
    {
        var sum = 0.0;
        for (var j = 0; j <= m; j++)
        {
            sum += w[(n * (m + 1)) + j];
        }

        return sum / (m + 1);
    }

    private static (ParticleWorld World, QuadraticBending Bending) Sheet(double[] vertices, int[] triangles, double rigidity)
    {
        var mesh = new WeldedMesh(vertices, triangles);
        var world = new ParticleWorld();
        for (var i = 0; i < mesh.ParticleCount; i++)
        {
            world.AddParticle(mesh.ParticlePosition(i), 1);
        }

        var bending = new QuadraticBending(world);
        PlateBending.AddSheet(bending, mesh.ParticleTriangles, mesh.ParticlePositions, 0, rigidity);
        return (world, bending);
    }

    private static double Area(double[] vertices, int[] triangles)
    {
        var mesh = new WeldedMesh(vertices, triangles);
        var area = 0.0;
        for (var t = 0; t < mesh.TriangleCount; t++)
        {
            area += mesh.TriangleArea(t);
        }

        return area;
    }
}
