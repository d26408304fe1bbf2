using System;
using System.Collections.Generic;

namespace ParticlePhysics.Contacts;

/// <summary>
/// Closed and open triangle meshes of known shape for the tests, the benchmarks and the samples: a box, a geodesic
/// sphere, a square grid. Triangles are wound counter-clockwise seen from outside (above, for the grid).
/// </summary>
internal static class StandardMeshes
{
    /// <summary>The box of half extents h around the origin: 8 vertices, 12 triangles.</summary>
    public static void Box(Vector3d h, out double[] vertices, out int[] triangles)
    {
        vertices = new double[24];
        for (var i = 0; i < 8; i++)
        {
            vertices[3 * i] = (i & 1) == 0 ? -h.X : h.X;
            vertices[(3 * i) + 1] = (i & 2) == 0 ? -h.Y : h.Y;
            vertices[(3 * i) + 2] = (i & 4) == 0 ? -h.Z : h.Z;
        }

        triangles = new[]
        {
            0, 4, 6, 0, 6, 2, // -x
            1, 3, 7, 1, 7, 5, // +x
            0, 1, 5, 0, 5, 4, // -y
            2, 6, 7, 2, 7, 3, // +y
            0, 2, 3, 0, 3, 1, // -z
            4, 5, 7, 4, 7, 6, // +z
        };
    }

    /// <summary>
    /// The icosahedron of circumradius R around the origin with each triangle split into four
    /// <paramref name="subdivisions"/> times, the new vertices pushed out to the sphere: 20 4^k triangles (1,280 for k = 3).
    /// </summary>
    public static void Icosphere(double radius, int subdivisions, out double[] vertices, out int[] triangles)
    {
        var t = (1.0 + Math.Sqrt(5.0)) / 2.0;
        var points = new List<Vector3d>
        {
            new(-1, t, 0), new(1, t, 0), new(-1, -t, 0), new(1, -t, 0),
            new(0, -1, t), new(0, 1, t), new(0, -1, -t), new(0, 1, -t),
            new(t, 0, -1), new(t, 0, 1), new(-t, 0, -1), new(-t, 0, 1),
        };
        for (var i = 0; i < points.Count; i++)
        {
            points[i] = points[i] / points[i].Length;
        }

        var faces = new List<int>
        {
            0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8,
            3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1,
        };
        for (var level = 0; level < subdivisions; level++)
        {
            var middles = new Dictionary<long, int>();
            var next = new List<int>(4 * faces.Count);
            for (var f = 0; f < faces.Count; f += 3)
            {
                int a = faces[f], b = faces[f + 1], c = faces[f + 2];
                var ab = Middle(a, b);
                var bc = Middle(b, c);
                var ca = Middle(c, a);
                next.AddRange(new[] { a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca });
            }

            faces = next;

            int Middle(int i, int j)
            {
                var key = ((long)Math.Min(i, j) << 32) | (uint)Math.Max(i, j);
                if (!middles.TryGetValue(key, out var m))
                {
                    var p = points[i] + points[j];
                    m = points.Count;
                    points.Add(p / p.Length);
                    middles[key] = m;
                }

                return m;
            }
        }

        vertices = new double[3 * points.Count];
        for (var i = 0; i < points.Count; i++)
        {
            vertices[3 * i] = radius * points[i].X;
            vertices[(3 * i) + 1] = radius * points[i].Y;
            vertices[(3 * i) + 2] = radius * points[i].Z;
        }

        triangles = faces.ToArray();
    }

    /// <summary>
    /// A square grid of n x n cells of side <paramref name="cell"/> in the plane y = 0 from the origin towards +x and
    /// +z, two triangles per cell facing +y, with heights from <paramref name="height"/>(x, z) if given.
    /// </summary>
    public static void Grid(int n, double cell, Func<double, double, double>? height, out double[] vertices, out int[] triangles)
    {
        vertices = new double[3 * (n + 1) * (n + 1)];
        for (var i = 0; i <= n; i++)
        {
            for (var j = 0; j <= n; j++)
            {
                var v = (i * (n + 1)) + j;
                vertices[3 * v] = j * cell;
                vertices[(3 * v) + 1] = height?.Invoke(j * cell, i * cell) ?? 0.0;
                vertices[(3 * v) + 2] = i * cell;
            }
        }

        triangles = new int[6 * n * n];
        var k = 0;
        for (var i = 0; i < n; i++)
        {
            for (var j = 0; j < n; j++)
            {
                var v = (i * (n + 1)) + j;
                var w = v + n + 1;
                triangles[k++] = v;
                triangles[k++] = w;
                triangles[k++] = v + 1;
                triangles[k++] = v + 1;
                triangles[k++] = w;
                triangles[k++] = w + 1;
            }
        }
    }
}
