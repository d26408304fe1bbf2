using System;
using System.Collections.Generic;
using MathNet.Numerics.LinearAlgebra;
using ParticlePhysics.Cloth;
using ParticlePhysics.Forces;

namespace ParticlePhysics.Tests.Cloth;

/// <summary>Meshes, loads and an independent static solver for the mesh-cloth tests.</summary>
internal static class ClothMeshes
{
    /// <summary>
    /// A strip of (n + 1) x (m + 1) vertices in the plane y = 0, rows along x at x0 + i dx, columns along z at j dz
    /// (vertex i (m + 1) + j), each cell split along one diagonal. With <paramref name="jitter"/> &gt; 0 the vertices of
    /// rows 2 to n - 1 move at random by up to jitter dx along x and (inner columns) jitter dz along z.
    /// </summary>
    public static (double[] Vertices, int[] Triangles) Strip(int n, int m, double dx, double dz, double x0 = 0, double jitter = 0, int seed = 1)
    {
        var random = new Random(seed);
        var vertices = new List<double>();
        for (var i = 0; i <= n; i++)
        {
            for (var j = 0; j <= m; j++)
            {
                double x = x0 + (i * dx), z = j * dz;
                if (jitter > 0 && i >= 2 && i < n)
                {
                    x += jitter * dx * ((2 * random.NextDouble()) - 1);
                    if (j > 0 && j < m)
                    {
                        z += jitter * dz * ((2 * random.NextDouble()) - 1);
                    }
                }

                vertices.AddRange(new[] { x, 0.0, z });
            }
        }

        var triangles = new List<int>();
        for (var i = 0; i < n; i++)
        {
            for (var j = 0; j < m; j++)
            {
                int a = (i * (m + 1)) + j, b = a + 1, c = a + m + 1, d = c + 1;
                triangles.AddRange(new[] { a, b, c, b, d, c });
            }
        }

        return (vertices.ToArray(), triangles.ToArray());
    }

    /// <summary>A random triangulation of the unit square: a jittered grid whose cells take either diagonal at random.</summary>
    public static (double[] Vertices, int[] Triangles) RandomSquare(int n, int seed)
    {
        var random = new Random(seed);
        var h = 1.0 / n;
        var vertices = new List<double>();
        for (var i = 0; i <= n; i++)
        {
            for (var j = 0; j <= n; j++)
            {
                double x = i * h, z = j * h;
                if (i > 0 && i < n && j > 0 && j < n)
                {
                    x += 0.3 * h * ((2 * random.NextDouble()) - 1);
                    z += 0.3 * h * ((2 * random.NextDouble()) - 1);
                }

                vertices.AddRange(new[] { x, 0.0, z });
            }
        }

        var triangles = new List<int>();
        for (var i = 0; i < n; i++)
        {
            for (var j = 0; j < n; j++)
            {
                int a = (i * (n + 1)) + j, b = a + 1, c = a + n + 1, d = c + 1;
                triangles.AddRange(random.Next(2) == 0 ? new[] { a, b, c, b, d, c } : new[] { a, b, d, a, d, c });
            }
        }

        return (vertices.ToArray(), triangles.ToArray());
    }

    /// <summary>
    /// The first-order static deflection of a sheet or rope under its own weight: Q w = -m g on the free particles
    /// (those not in <paramref name="pinned"/>), solved densely by MathNet's LU from the entries of the library's Q.
    /// </summary>
    public static double[] StaticDeflection(QuadraticBending bending, double[] masses, bool[] pinned, double g)
    {
        var free = new List<int>();
        for (var i = 0; i < masses.Length; i++)
        {
            if (!pinned[i])
            {
                free.Add(i);
            }
        }

        var matrix = Matrix<double>.Build.Dense(free.Count, free.Count, (r, c) => bending.MatrixEntry(free[r], free[c]));
        var load = Vector<double>.Build.Dense(free.Count, r => -masses[free[r]] * g);
        var solution = matrix.LU().Solve(load);
        var w = new double[masses.Length];
        for (var r = 0; r < free.Count; r++)
        {
            w[free[r]] = solution[r];
        }

        return w;
    }
}

/// <summary>Constant forces on chosen particles: a strip's end pulled by nodal shares of a total force.</summary>
internal sealed class NodalLoads : IForceGenerator
{
    public List<(int Particle, Vector3d Force)> Loads { get; } = new();

    public void AddForces(in ParticleState state, Span<double> forces)
    {
        foreach (var (particle, force) in Loads)
        {
            forces[3 * particle] += force.X;
            forces[(3 * particle) + 1] += force.Y;
            forces[(3 * particle) + 2] += force.Z;
        }
    }
}
