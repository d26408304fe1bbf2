using System;
using ParticlePhysics.Aerodynamics;
using ParticlePhysics.Cloth;
using ParticlePhysics.Integrators;
using ParticlePhysics.Tests.Cloth;
using Xunit.Abstractions;

namespace ParticlePhysics.Tests.Aerodynamics;

/// <summary>
/// The air's drag and lift on cloth triangles (issue 30) against the scene contract's formulas, written out here a
/// second way, and against the exact results they imply: a flat plate's lift and drag at an angle of attack, and the
/// terminal velocity of a flat cloth falling face-down.
/// </summary>
public class TriangleAerodynamicsTests
{
    private readonly ITestOutputHelper _output;

    public TriangleAerodynamicsTests(ITestOutputHelper output) => _output = output;

    [Fact]
    public void A_triangle_in_a_flow_feels_exactly_the_contracts_drag_and_lift()
    {
        var random = new Random(11);
        for (var trial = 0; trial < 500; trial++)
        {
            var x = new[] { RandomVector(random, 1), RandomVector(random, 1), RandomVector(random, 1) };
            var v = new[] { RandomVector(random, 3), RandomVector(random, 3), RandomVector(random, 3) };
            var air = new Air(0.5 + random.NextDouble(), RandomVector(random, 10), random.NextDouble() * 2, random.NextDouble());
            var (world, aerodynamics) = OneTriangle(x, v, air);
            var forces = new double[9];
            aerodynamics.AddForces(world.View(), forces);

            var expected = ContractForce(x, v, air) / 3.0;
            var scale = Math.Max(1e-300, expected.Length);
            for (var corner = 0; corner < 3; corner++)
            {
                var f = new Vector3d(forces[3 * corner], forces[(3 * corner) + 1], forces[(3 * corner) + 2]);
                Assert.True((f - expected).Length <= 1e-13 * scale, $"trial {trial}, corner {corner}: {f} against {expected}");
            }
        }
    }

    [Theory]
    [InlineData(5.0)]
    [InlineData(30.0)]
    [InlineData(60.0)]
    [InlineData(89.0)]
    public void A_plate_at_an_angle_of_attack_feels_its_lift_and_drag(double degrees)
    {
        // A right triangle of area 1/2 in the plane z = 0 tilted by alpha about z, in a flow s along x.
        const double rho = 1.2, cd = 1.1, cl = 0.8, s = 7.0;
        var alpha = degrees * Math.PI / 180;
        var along = new Vector3d(Math.Cos(alpha), Math.Sin(alpha), 0);
        var x = new[] { Vector3d.Zero, along, new Vector3d(0, 0, 1) };
        var v = new[] { Vector3d.Zero, Vector3d.Zero, Vector3d.Zero };
        var (world, aerodynamics) = OneTriangle(x, v, new Air(rho, new Vector3d(s, 0, 0), cd, cl));
        var forces = new double[9];
        aerodynamics.AddForces(world.View(), forces);
        var total = new Vector3d(forces[0] + forces[3] + forces[6], forces[1] + forces[4] + forces[7], forces[2] + forces[5] + forces[8]);

        // The plate rises downstream, so the flow meets its upper face (normal n, up and upstream): the pressure drag
        // pushes along -n and the lift is down, across the flow: w = n - (v_n / s^2) v_rel = (0, cos alpha, 0).
        var normal = new Vector3d(-Math.Sin(alpha), Math.Cos(alpha), 0);
        var q = 0.5 * rho * s * s * 0.5;
        var lift = q * cl * Math.Sin(alpha);
        var drag = q * cd * Math.Sin(alpha) * Math.Sin(alpha);
        var expected = (-drag * normal) + new Vector3d(0, -lift, 0);
        _output.WriteLine($"alpha {degrees} deg: force {total}, expected drag {drag:R} along -n and lift {lift:R} down");
        Assert.True((total - expected).Length <= 1e-12 * expected.Length, $"{total} against {expected}");
    }

    [Fact]
    public void Reversing_a_triangles_winding_changes_no_bit_of_its_force()
    {
        var random = new Random(4);
        var x = new[] { RandomVector(random, 1), RandomVector(random, 1), RandomVector(random, 1) };
        var v = new[] { RandomVector(random, 2), RandomVector(random, 2), RandomVector(random, 2) };
        var air = new Air(1.2, new Vector3d(3, -1, 2), 1.0, 0.7);
        var (world, forward) = OneTriangle(x, v, air);
        var reversed = new TriangleAerodynamics(world, air);
        reversed.Add(0, 2, 1);
        var a = new double[9];
        var b = new double[9];
        forward.AddForces(world.View(), a);
        reversed.AddForces(world.View(), b);
        Assert.Equal(a, b);
    }

    [Fact]
    public void The_jacobian_is_the_drags_exact_velocity_derivative_and_its_blocks_are_the_products()
    {
        var (vertices, triangles) = ClothMeshes.RandomSquare(3, 2);
        var mesh = new WeldedMesh(vertices, triangles);
        var air = new Air(1.2, new Vector3d(2, 5, -1), 1.3, 0.0);
        var cloth = new MeshClothBuilder(mesh) { Air = air, TotalMass = 0.2 }.Build();
        var world = cloth.System;
        var aerodynamics = cloth.Aerodynamics!;
        var random = new Random(8);
        var n = world.Count;
        for (var i = 0; i < n; i++)
        {
            var p = world.GetPosition(i);
            world.SetPosition(i, new Vector3d(p.X, 0.2 * random.NextDouble(), p.Z));
            world.SetVelocity(i, RandomVector(random, 1));
        }

        var x = world.Positions.ToArray();
        var v = world.Velocities.ToArray();
        var w = new double[3 * n];
        for (var k = 0; k < w.Length; k++)
        {
            w[k] = (2 * random.NextDouble()) - 1;
        }

        // Central differences of a force quadratic in v (while no v_n changes sign) are exact but for rounding.
        const double step = 1e-5;
        var plus = Forces(aerodynamics, world, x, Shift(v, w, step));
        var minus = Forces(aerodynamics, world, x, Shift(v, w, -step));
        var product = new double[3 * n];
        var positionPart = new double[3 * n];
        aerodynamics.Linearize(new ParticleState(0, x, v, world.Masses, world.InverseMasses), 0.0, 1.0, positionPart);
        aerodynamics.AddJacobianProduct(w, product);
        for (var k = 0; k < product.Length; k++)
        {
            Assert.Equal((plus[k] - minus[k]) / (2 * step), product[k], 1e-8);
            Assert.Equal(0.0, positionPart[k]);
        }

        // Diagonal and coupling blocks assembled: the product's matrix, symmetric and negative semi-definite.
        aerodynamics.Linearize(new ParticleState(0, x, v, world.Masses, world.InverseMasses), 0.7, 0.3, positionPart);
        var dense = new double[3 * n, 3 * n];
        for (var j = 0; j < 3 * n; j++)
        {
            var unit = new double[3 * n];
            unit[j] = 1;
            var column = new double[3 * n];
            aerodynamics.AddJacobianProduct(unit, column);
            for (var k = 0; k < 3 * n; k++)
            {
                dense[k, j] = column[k];
            }
        }

        var diagonal = new double[9 * n];
        aerodynamics.AddDiagonalBlocks(diagonal);
        var pairs = aerodynamics.CouplingCount;
        var first = new int[pairs];
        var second = new int[pairs];
        aerodynamics.WriteCouplings(first, second);
        var blocks = new double[18 * pairs];
        var forward = new int[pairs];
        var backward = new int[pairs];
        for (var c = 0; c < pairs; c++)
        {
            forward[c] = 2 * c;
            backward[c] = (2 * c) + 1;
        }

        aerodynamics.AddCouplingBlocks(blocks, forward, backward);
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
                Assert.Equal(dense[r, c], assembled[r, c], 1e-12);
                Assert.Equal(dense[r, c], dense[c, r], 1e-12);
            }
        }

        for (var trial = 0; trial < 20; trial++)
        {
            var z = new double[3 * n];
            for (var k = 0; k < z.Length; k++)
            {
                z[k] = (2 * random.NextDouble()) - 1;
            }

            var jz = new double[3 * n];
            aerodynamics.AddJacobianProduct(z, jz);
            var quadratic = 0.0;
            for (var k = 0; k < z.Length; k++)
            {
                quadratic += z[k] * jz[k];
            }

            Assert.True(quadratic <= 1e-15, $"z^T J z = {quadratic}");
        }
    }

    [Theory]
    [InlineData("xpbd", 1.0 / 60)]
    [InlineData("implicit-euler", 1.0 / 60)]
    [InlineData("semi-implicit-euler", 1e-3)]
    [InlineData("rk4", 1e-3)]
    public void A_flat_cloth_falling_face_down_reaches_its_terminal_velocity(string integrator, double dt)
    {
        // 0.5 m x 0.5 m, 50 g: v_t = sqrt(2 m g / (rho C_d A)) = 1.808 m/s, reached within 1 % after about 4 v_t / g.
        const double mass = 0.05, rho = 1.2, cd = 1.2, side = 0.5;
        var (vertices, triangles) = ClothMeshes.RandomSquare(6, 3);
        for (var k = 0; k < vertices.Length; k++)
        {
            vertices[k] *= side;
        }

        var air = new Air(rho, Vector3d.Zero, cd, 0.0); // with lift, the slightest tilt meets the lift of a plate face-on, and it tumbles as paper does
        var cloth = new MeshClothBuilder(new WeldedMesh(vertices, triangles)) { Air = air, TotalMass = mass, Modulus = 200 }.Build();
        var world = cloth.System;
        var method = IntegratorCatalog.Create(integrator);
        var steps = (int)Math.Round(1.5 / dt);
        for (var s = 0; s < steps; s++)
        {
            world.Step(method, dt);
        }

        var exact = Math.Sqrt(2 * mass * 9.81 / (rho * cd * side * side));
        double lowest = double.MaxValue, highest = double.MinValue;
        for (var i = 0; i < world.Count; i++)
        {
            lowest = Math.Min(lowest, -world.GetVelocity(i).Y);
            highest = Math.Max(highest, -world.GetVelocity(i).Y);
        }

        _output.WriteLine($"{integrator}: fall speed {lowest:R} to {highest:R} m/s, exact {exact:R} ({((lowest / exact) - 1) * 100:F4} %)");
        Assert.InRange(lowest, (1 - 1e-5) * exact, (1 + 1e-5) * exact); // the issue asks 1 %; 1.5 s is nine time constants v_t / g
        Assert.InRange(highest, (1 - 1e-5) * exact, (1 + 1e-5) * exact);
    }

    internal static Vector3d ContractForce(Vector3d[] x, Vector3d[] v, Air air)
    {
        // ../shared/SCENES.md, "Formulas fixed by this contract", word for word.
        var cross = Vector3d.Cross(x[1] - x[0], x[2] - x[0]);
        var area = cross.Length / 2;
        var n = cross / cross.Length;
        var relative = air.Velocity - ((v[0] + v[1] + v[2]) / 3);
        var s = relative.Length;
        var vn = Vector3d.Dot(relative, n);
        var drag = 0.5 * air.Density * air.DragCoefficient * area * Math.Abs(vn) * vn * n;
        if (s == 0)
        {
            return drag;
        }

        var w = n - (vn / (s * s) * relative);
        if (w.Length == 0)
        {
            return drag;
        }

        return drag + (0.5 * air.Density * air.LiftCoefficient * area * vn * s * (w / w.Length));
    }

    private static (ParticleWorld World, TriangleAerodynamics Aerodynamics) OneTriangle(Vector3d[] x, Vector3d[] v, Air air)
    {
        var world = new ParticleWorld(3);
        for (var i = 0; i < 3; i++)
        {
            world.AddParticle(x[i], v[i], 1.0);
        }

        var aerodynamics = new TriangleAerodynamics(world, air);
        aerodynamics.Add(0, 1, 2);
        return (world, aerodynamics);
    }

    private static Vector3d RandomVector(Random random, double scale) =>
        new(scale * ((2 * random.NextDouble()) - 1), scale * ((2 * random.NextDouble()) - 1), scale * ((2 * random.NextDouble()) - 1));

    private static double[] Shift(double[] x, double[] w, double step)
    {
        var result = (double[])x.Clone();
        for (var k = 0; k < x.Length; k++)
        {
            result[k] += step * w[k];
        }

        return result;
    }

    private static double[] Forces(TriangleAerodynamics aerodynamics, ParticleWorld world, double[] x, double[] v)
    {
        var forces = new double[x.Length];
        aerodynamics.AddForces(new ParticleState(0, x, v, world.Masses, world.InverseMasses), forces);
        return forces;
    }
}
