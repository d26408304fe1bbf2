using System;
using ParticlePhysics.Forces;

namespace ParticlePhysics.Tests.Implicit;

/// <summary>
/// Each built-in force's Jacobian against central finite differences of its own forces: df/dx columns by moving one
/// coordinate, df/dv columns by changing one velocity. Products, the K v term and the diagonal blocks are all checked.
/// </summary>
public class JacobianTests
{
    private const double H = 1e-6;

    public static TheoryData<string> Forces() => new() { "spring-network", "undamped-springs", "anchored-spring", "zero-length", "drag", "drag-subset", "dampers", "gravity" };

    [Theory]
    [MemberData(nameof(Forces))]
    public void Position_and_velocity_jacobians_match_finite_differences(string force)
    {
        var (system, generator) = Build(force, relativeVelocities: force != "spring-network" && force != "anchored-spring");
        var jacobian = Assert.IsAssignableFrom<IForceJacobian>(generator);
        var n = system.CoordinateCount;
        var (fdX, fdV) = FiniteDifferenceJacobians(system, generator);

        // Products with unit vectors give the columns of a df/dx + b df/dv.
        foreach (var (a, b) in new[] { (1.0, 0.0), (0.0, 1.0), (0.3, 0.7) })
        {
            var view = system.View();
            jacobian.Linearize(view, a, b, new double[n]);
            for (var col = 0; col < n; col++)
            {
                var w = new double[n];
                w[col] = 1.0;
                var product = new double[n];
                jacobian.AddJacobianProduct(w, product);
                for (var row = 0; row < n; row++)
                {
                    var expected = (a * fdX[row, col]) + (b * fdV[row, col]);
                    Assert.True(
                        Math.Abs(product[row] - expected) < 1e-6 * (1 + Math.Abs(expected)),
                        $"{force}: ({a} dx + {b} dv) J[{row},{col}] = {product[row]}, finite differences {expected}");
                }
            }

            // Diagonal blocks are the 3 x 3 blocks of the same matrix on the diagonal.
            var blocks = new double[3 * n];
            jacobian.AddDiagonalBlocks(blocks);
            for (var i = 0; i < system.Count; i++)
            {
                for (var r = 0; r < 3; r++)
                {
                    for (var c = 0; c < 3; c++)
                    {
                        var expected = (a * fdX[(3 * i) + r, (3 * i) + c]) + (b * fdV[(3 * i) + r, (3 * i) + c]);
                        Assert.Equal(expected, blocks[(9 * i) + (3 * r) + c], 5);
                    }
                }
            }

            // Coupling blocks (what the multigrid assembles): every off-diagonal block of the same matrix, summed over
            // the couplings of each pair, with J_ji the transpose of J_ij; pairs without a coupling must be zero.
            if (generator is IJacobianCouplings couplings)
            {
                var count = couplings.CouplingCount;
                int[] first = new int[count], second = new int[count], forward = new int[count], backward = new int[count];
                couplings.WriteCouplings(first, second);
                for (var e = 0; e < count; e++)
                {
                    forward[e] = 2 * e;
                    backward[e] = (2 * e) + 1;
                }

                var assembled = new double[18 * count];
                couplings.AddCouplingBlocks(assembled, forward, backward);
                var dense = new double[n, n];
                for (var e = 0; e < count; e++)
                {
                    for (var r = 0; r < 3; r++)
                    {
                        for (var c = 0; c < 3; c++)
                        {
                            dense[(3 * first[e]) + r, (3 * second[e]) + c] += assembled[(18 * e) + (3 * r) + c];
                            dense[(3 * second[e]) + r, (3 * first[e]) + c] += assembled[(18 * e) + 9 + (3 * r) + c];
                        }
                    }
                }

                for (var row = 0; row < n; row++)
                {
                    for (var col = 0; col < n; col++)
                    {
                        if (row / 3 != col / 3)
                        {
                            var expected = (a * fdX[row, col]) + (b * fdV[row, col]);
                            Assert.True(
                                Math.Abs(dense[row, col] - expected) < 1e-6 * (1 + Math.Abs(expected)),
                                $"{force}: coupling block J[{row},{col}] = {dense[row, col]}, finite differences {expected}");
                        }
                    }
                }
            }
        }

        // K v, accumulated by Linearize, is df/dx applied to the state's velocities.
        var kv = new double[n];
        jacobian.Linearize(system.View(), 1.0, 0.0, kv);
        var velocities = system.Velocities.ToArray();
        for (var row = 0; row < n; row++)
        {
            var expected = 0.0;
            for (var col = 0; col < n; col++)
            {
                expected += fdX[row, col] * velocities[col];
            }

            Assert.True(Math.Abs(kv[row] - expected) < 1e-6 * (1 + Math.Abs(expected)), $"{force}: (K v)[{row}] = {kv[row]} vs {expected}");
        }
    }

    [Fact]
    public void A_compressed_spring_clamps_its_transverse_stiffness_so_the_matrix_stays_definite()
    {
        var system = new ParticleWorld();
        system.AddParticle(new Vector3d(0.3, 0.4, 0), 1);
        system.AddParticle(Vector3d.Zero, 1);
        var springs = new SpringNetwork(system);
        springs.Add(0, 1, stiffness: 10, restLength: 1); // l = 0.5 < L: compressed
        system.AddForce(springs);
        springs.Linearize(system.View(), 1.0, 0.0, new double[6]);
        var blocks = new double[18];
        springs.AddDiagonalBlocks(blocks);

        // Unclamped, the transverse term -k (1 - L/l) = +10 would make df/dx positive across the spring.
        // Clamped: J = -k u u^T, whose eigenvalues are -k along u and 0 across it.
        var u = new Vector3d(0.6, 0.8, 0);
        var across = new Vector3d(-0.8, 0.6, 0);
        Assert.Equal(-10, Quadratic(blocks, u), 12);
        Assert.Equal(0, Quadratic(blocks, across), 12);
    }

    [Fact]
    public void A_spring_of_zero_length_linearises_without_nan()
    {
        var system = new ParticleWorld();
        system.AddParticle(new Vector3d(1, 1, 1), 1);
        system.AddParticle(new Vector3d(1, 1, 1), 1);
        var springs = new SpringNetwork(system);
        springs.Add(0, 1, 5, restLength: 0);
        springs.Add(0, 1, 5, restLength: 0.5, damping: 2);
        system.AddForce(springs);
        var kv = new double[6];
        springs.Linearize(system.View(), 1.0, 1.0, kv);
        var product = new double[6];
        springs.AddJacobianProduct(new double[] { 1, 2, 3, 0, 0, 0 }, product);
        Assert.All(product, value => Assert.True(double.IsFinite(value)));
        Assert.Equal(new[] { -5.0, -10, -15, 5, 10, 15 }, product); // the zero-rest-length spring's -k I
    }

    private static double Quadratic(double[] blocks, Vector3d u)
    {
        double[] v = { u.X, u.Y, u.Z };
        var sum = 0.0;
        for (var r = 0; r < 3; r++)
        {
            for (var c = 0; c < 3; c++)
            {
                sum += v[r] * blocks[(3 * r) + c] * v[c];
            }
        }

        return sum;
    }

    /// <summary>A small system of four particles in general position, with the force under test.</summary>
    private static (ParticleWorld System, IForceGenerator Generator) Build(string force, bool relativeVelocities)
    {
        var system = new ParticleWorld();
        system.AddParticle(new Vector3d(0.1, 0.2, -0.3), new Vector3d(0.5, -0.2, 0.1), 0.7);
        system.AddParticle(new Vector3d(1.3, -0.1, 0.4), new Vector3d(-0.3, 0.4, 0.2), 1.1);
        system.AddParticle(new Vector3d(0.4, 1.2, 0.9), new Vector3d(0.2, 0.1, -0.6), 0.5);
        system.AddParticle(new Vector3d(-0.7, 0.5, 0.2), new Vector3d(0.1, 0.3, 0.3), 0.9);
        if (force == "anchored-spring")
        {
            // The anchor is still, so axial damping's (omitted) position derivative vanishes only at rest.
            for (var i = 0; i < 4; i++)
            {
                system.SetVelocity(i, Vector3d.Zero);
            }
        }
        else if (!relativeVelocities)
        {
            // Axial damping's position derivative is left out of the Jacobian (not symmetric); it vanishes when the
            // ends move together, so springs with damping are checked at a common velocity.
            for (var i = 0; i < 4; i++)
            {
                system.SetVelocity(i, new Vector3d(0.2, -0.1, 0.3));
            }
        }

        IForceGenerator generator;
        switch (force)
        {
            case "spring-network":
                var springs = new SpringNetwork(system);
                springs.Add(0, 1, 12, 0.8, 0.4);   // stretched
                springs.Add(1, 2, 7, 1.2, 0.3);    // stretched
                springs.Add(2, 3, 5, 0.5, 0.2);    // stretched
                springs.Add(0, 3, 9, 0.0, 0.1);    // zero rest length
                generator = springs;
                break;
            case "undamped-springs":
                // Without axial damping the Jacobian is exact at any velocities, so K v is checked with relative motion.
                var undamped = new SpringNetwork(system);
                undamped.Add(0, 1, 12, 0.8);
                undamped.Add(1, 2, 7, 1.2);
                undamped.Add(0, 3, 9, 0.0);
                undamped.AddAnchored(3, new Vector3d(0, -1, 0), 3, 0.2);
                generator = undamped;
                break;
            case "anchored-spring":
                var anchored = new SpringNetwork(system);
                anchored.AddAnchored(0, new Vector3d(2, 2, 2), 6, 0.5, 0.3);
                anchored.AddAnchored(2, new Vector3d(-1, 0, 0), 4, 0.7, 0);
                generator = anchored;
                break;
            case "zero-length":
                var zero = new ZeroLengthSprings(system);
                zero.Add(0, 1, 3);
                zero.Add(1, 3, 2);
                zero.AddAnchored(2, new Vector3d(1, 1, 1), 4);
                generator = zero;
                break;
            case "drag":
                generator = new LinearDrag(0.8);
                break;
            case "drag-subset":
                generator = new LinearDrag(0.8, system, new[] { 1, 3 });
                break;
            case "dampers":
                var dampers = new Dampers(system);
                dampers.Add(0, 2, 0.6);
                dampers.Add(1, 2, 0.9);
                generator = dampers;
                break;
            case "gravity":
                generator = new Gravity();
                break;
            default:
                throw new ArgumentOutOfRangeException(nameof(force), force, "unknown force");
        }

        system.AddForce(generator);
        return (system, generator);
    }

    private static (double[,] X, double[,] V) FiniteDifferenceJacobians(ParticleWorld system, IForceGenerator generator)
    {
        var n = system.CoordinateCount;
        var x = system.Positions.ToArray();
        var v = system.Velocities.ToArray();
        var jx = new double[n, n];
        var jv = new double[n, n];
        for (var col = 0; col < n; col++)
        {
            foreach (var (target, into) in new[] { (x, jx), (v, jv) })
            {
                var original = target[col];
                target[col] = original + H;
                var plus = Forces(system, generator, x, v);
                target[col] = original - H;
                var minus = Forces(system, generator, x, v);
                target[col] = original;
                for (var row = 0; row < n; row++)
                {
                    into[row, col] = (plus[row] - minus[row]) / (2 * H);
                }
            }
        }

        return (jx, jv);
    }

    private static double[] Forces(ParticleWorld system, IForceGenerator generator, double[] x, double[] v)
    {
        var forces = new double[x.Length];
        generator.AddForces(new ParticleState(0, x, v, system.Masses, system.InverseMasses), forces);
        return forces;
    }
}
