using System;
using System.Collections.Generic;
using ParticlePhysics.Forces;

namespace ParticlePhysics.Cloth;

/// <summary>
/// Kirchhoff plate bending of flexural rigidity D on a triangle mesh, as elements of a <see cref="QuadraticBending"/>:
/// one per triangle, its curvature from the jumps of the surface's slope across its three edges.
/// </summary>
/// <remarks>
/// <para>
/// The continuum: a flat plate bent out of its plane by w(u, v) stores (D / 2) integral [(1 - nu) |Hess w|^2 +
/// nu (Laplacian w)^2] dA; for isometric bending (cloth barely stretches) Gaussian curvature vanishes and every nu gives
/// (D / 2) integral (kappa_1 + kappa_2)^2 dA, D A / (2 R^2) for a cylinder of radius R. We take nu = 0, (D / 2) integral
/// |Hess x|^2 dA summed over the coordinates x, y, z of the embedding: for an isometry Hess x_c = II n_c, so it is
/// (D / 2) integral (kappa_1^2 + kappa_2^2) dA, and for small deflections of a flat sheet (D / 2) integral |Hess w|^2 dA,
/// whose strip clamped at one end sags as a beam of rigidity D b: rho_A g L^4 / (8 D).
/// </para>
/// <para>
/// The discrete Hessian H_T of a triangle T, over T's corners and the far corners of its neighbours across its edges
/// (the rotation-free plate triangles of Onate and Zarate, 2000). A triangle with three neighbours takes the Hessian of
/// the quadratic through those six points, unfolded into T's plane (each far corner placed by its distances to the
/// edge's ends, on the far side): with f = c0 u^2 + c1 u v + c2 v^2 + c3 u + c4 v + c5 and V the 6 x 6 matrix of
/// monomials, c = V^-1 f and H_T = [[2 c0, c1], [c1, 2 c2]], a fixed linear function of the six values, exact for
/// every quadratic on any triangulation. A triangle with fewer neighbours (at a boundary) takes the basic plate
/// triangle's form instead: by the divergence theorem, integral_T Hess f = boundary integral of grad f (x) n, with
/// grad f on each edge the mean of the piecewise-linear slopes of T and of its neighbour; the tangential slope is
/// continuous, so only the jump j_e of the normal slope survives and H_T = (1 / (2 A_T)) sum_e l_e j_e n_e n_e^T.
/// With a, b the edge's ends, k the corner of T opposite it and o the neighbour's, d_k = 2 A_T / l_e and
/// d_o = 2 A_o / l_e their heights over the edge and t_k, t_o where their feet fall along it (0 at a, 1 at b):
/// j_e = (f_o - (1 - t_o) f_a - t_o f_b) / d_o + (f_k - (1 - t_k) f_a - t_k f_b) / d_k. A boundary edge has no jump: a
/// free edge carries no bending moment, as Kirchhoff's does. On a regular grid both forms are the same stencil. Both
/// are intrinsic (edge lengths and areas only) and zero for any f linear in the flattened patch, so rigid motions and
/// in-plane stretches of a flat sheet cost nothing. The element is c = H_T in Voigt form (H_uu, H_vv, sqrt(2) H_uv),
/// stiffness s = D A_T: energy (D A_T / 2) |H_T|^2. An edge that three or more triangles share is treated as a
/// boundary edge. The rest shape is flat: a mesh curved as given is a flat sheet bent into that shape.
/// </para>
/// <para>
/// Measured (PlateBendingTests): a cantilever strip's sag is within 0.6 % of rho_A g L^4 / (8 D) at 10 segments and
/// converges at second order on a regular grid, and on vertices perturbed at random by a quarter of the spacing it is
/// within 0.4 % from 20 segments on; a cylinder's energy converges at first order (the boundary triangles'). Cells
/// whose diagonals are flipped at random make the sheet about 6 % too soft at 20 to 40 segments: the six-point
/// quadratic then controls some short oscillations weakly.
/// </para>
/// </remarks>
public static class PlateBending
{

    /// <summary>
    /// Adds the elements of a sheet to <paramref name="bending"/>: <paramref name="triangles"/> (3 indices each into the
    /// sheet's particles), whose rest positions are <paramref name="restPositions"/> (3 values per particle), the sheet's
    /// particle i being the world's particle <paramref name="firstParticle"/> + i.
    /// </summary>
    /// <param name="bending">The energy to add to.</param>
    /// <param name="triangles">The sheet's triangles, 3 particle indices each (non-degenerate).</param>
    /// <param name="restPositions">x, y, z of each of the sheet's particles at rest.</param>
    /// <param name="firstParticle">The world's index of the sheet's particle 0.</param>
    /// <param name="rigidity">D, in N m: finite and &gt;= 0.</param>
    /// <returns>The number of elements added (the triangles with at least one neighbour).</returns>
    public static int AddSheet(
        QuadraticBending bending, ReadOnlySpan<int> triangles, ReadOnlySpan<double> restPositions, int firstParticle, double rigidity)
    {
        Guard.NotNull(bending, nameof(bending));
        Guard.NonNegativeFinite(rigidity, nameof(rigidity));
        var elements = Stencils(triangles, restPositions);
        foreach (var element in elements)
        {
            for (var v = 0; v < element.Particles.Length; v++)
            {
                element.Particles[v] += firstParticle;
            }

            bending.Add(element.Particles, element.Weights, rigidity * element.Area);
        }

        return elements.Count;
    }

    /// <summary>The elements of a sheet: particles (local), weights (3 rows) and area, one per triangle with a neighbour.</summary>
    internal static List<(int[] Particles, double[] Weights, double Area)> Stencils(ReadOnlySpan<int> triangles, ReadOnlySpan<double> restPositions)
    {
        var tri = triangles.ToArray();
        var x = restPositions.ToArray();
        var count = tri.Length / 3;

        // Each edge (smaller index, larger index) and the triangles that have it.
        var edges = new Dictionary<long, List<int>>();
        for (var t = 0; t < count; t++)
        {
            for (var k = 0; k < 3; k++)
            {
                var key = EdgeKey(tri[(3 * t) + ((k + 1) % 3)], tri[(3 * t) + ((k + 2) % 3)]);
                if (!edges.TryGetValue(key, out var list))
                {
                    list = new List<int>(2);
                    edges.Add(key, list);
                }

                list.Add(t);
            }
        }

        var result = new List<(int[], double[], double)>();
        var far = new int[3];
        var farU = new double[3];
        var farV = new double[3];
        var particles = new List<int>(6);
        var weights = new List<double[]>(6);
        for (var t = 0; t < count; t++)
        {
            particles.Clear();
            weights.Clear();
            var area = Area(x, tri[3 * t], tri[(3 * t) + 1], tri[(3 * t) + 2]);

            // T's own frame: u along its first edge, v in its plane normal to u.
            var p0 = Point(x, tri[3 * t]);
            var u = (Point(x, tri[(3 * t) + 1]) - p0) / (Point(x, tri[(3 * t) + 1]) - p0).Length;
            var normal = Vector3d.Cross(Point(x, tri[(3 * t) + 1]) - p0, Point(x, tri[(3 * t) + 2]) - p0);
            var v = Vector3d.Cross(normal, u);
            v /= v.Length;
            var interior = false;
            var neighbours = 0;
            for (var k = 0; k < 3; k++)
            {
                int ck = tri[(3 * t) + k], a = tri[(3 * t) + ((k + 1) % 3)], b = tri[(3 * t) + ((k + 2) % 3)];
                var list = edges[EdgeKey(a, b)];
                if (list.Count != 2)
                {
                    continue; // a boundary edge, or one of three or more triangles: no jump
                }

                var other = list[0] == t ? list[1] : list[0];
                var o = -1;
                for (var m = 0; m < 3; m++)
                {
                    var candidate = tri[(3 * other) + m];
                    if (candidate != a && candidate != b)
                    {
                        o = candidate;
                    }
                }

                interior = true;
                Vector3d pa = Point(x, a), pb = Point(x, b);
                var edge = pb - pa;
                var lengthSquared = edge.LengthSquared;
                var length = Math.Sqrt(lengthSquared);
                var dk = 2.0 * area / length;
                var tk = Vector3d.Dot(Point(x, ck) - pa, edge) / lengthSquared;
                var dO = 2.0 * Area(x, a, b, o) / length;
                var tO = Vector3d.Dot(Point(x, o) - pa, edge) / lengthSquared;

                // The outward normal of the edge in T's frame (away from k).
                double eu = Vector3d.Dot(edge, u) / length, ev = Vector3d.Dot(edge, v) / length;
                double nu = ev, nv = -eu;
                var toK = Point(x, ck) - pa;
                if ((nu * Vector3d.Dot(toK, u)) + (nv * Vector3d.Dot(toK, v)) > 0)
                {
                    nu = -nu;
                    nv = -nv;
                }

                // The far corner unfolded into T's plane: tO along the edge, dO beyond it.
                if (o != ck && Array.IndexOf(far, o, 0, neighbours) < 0)
                {
                    var au = Vector3d.Dot(pa - p0, u);
                    var av = Vector3d.Dot(pa - p0, v);
                    far[neighbours] = o;
                    farU[neighbours] = au + (tO * length * eu) + (dO * nu);
                    farV[neighbours] = av + (tO * length * ev) + (dO * nv);
                    neighbours++;
                }

                var scale = length / (2.0 * area);
                double m1 = scale * nu * nu, m2 = scale * nv * nv, m3 = scale * Math.Sqrt(2.0) * nu * nv;
                Accumulate(particles, weights, o, 1.0 / dO, m1, m2, m3);
                Accumulate(particles, weights, ck, 1.0 / dk, m1, m2, m3);
                Accumulate(particles, weights, a, -((1.0 - tO) / dO) - ((1.0 - tk) / dk), m1, m2, m3);
                Accumulate(particles, weights, b, -(tO / dO) - (tk / dk), m1, m2, m3);
            }

            if (neighbours == 3)
            {
                var p1 = Point(x, tri[(3 * t) + 1]) - p0;
                var p2 = Point(x, tri[(3 * t) + 2]) - p0;
                QuadraticFit(
                    particles,
                    weights,
                    new[] { tri[3 * t], tri[(3 * t) + 1], tri[(3 * t) + 2], far[0], far[1], far[2] },
                    new[] { 0.0, Vector3d.Dot(p1, u), Vector3d.Dot(p2, u), farU[0], farU[1], farU[2] },
                    new[] { 0.0, Vector3d.Dot(p1, v), Vector3d.Dot(p2, v), farV[0], farV[1], farV[2] },
                    Math.Sqrt(area));
            }

            if (!interior)
            {
                continue;
            }

            var n = particles.Count;
            var rows = new double[3 * n];
            for (var i = 0; i < n; i++)
            {
                rows[i] = weights[i][0];
                rows[n + i] = weights[i][1];
                rows[(2 * n) + i] = weights[i][2];
            }

            result.Add((particles.ToArray(), rows, area));
        }

        return result;
    }

    /// <summary>
    /// Replaces the weights by those of the Hessian of the quadratic through the six points (u, v): with
    /// f = c0 u^2 + c1 u v + c2 v^2 + c3 u + c4 v + c5 and V the 6 x 6 matrix of those monomials at the points (centred
    /// on the first three and scaled by <paramref name="size"/>), c = V^-1 f, so H = [[2 c0, c1], [c1, 2 c2]] is a
    /// linear function of f, exact for every quadratic. Left as they are when V is singular (six points on one conic).
    /// </summary>
    private static void QuadraticFit(List<int> particles, List<double[]> weights, int[] points, double[] u, double[] v, double size)
    {
        double cu = (u[0] + u[1] + u[2]) / 3.0, cv = (v[0] + v[1] + v[2]) / 3.0;
        var m = new double[6, 12];
        for (var i = 0; i < 6; i++)
        {
            double a = (u[i] - cu) / size, b = (v[i] - cv) / size;
            m[i, 0] = a * a;
            m[i, 1] = a * b;
            m[i, 2] = b * b;
            m[i, 3] = a;
            m[i, 4] = b;
            m[i, 5] = 1.0;
            m[i, 6 + i] = 1.0;
        }

        // Gauss-Jordan with partial pivoting: the right half becomes V^-1.
        for (var col = 0; col < 6; col++)
        {
            var pivot = col;
            for (var row = col + 1; row < 6; row++)
            {
                if (Math.Abs(m[row, col]) > Math.Abs(m[pivot, col]))
                {
                    pivot = row;
                }
            }

            if (!(Math.Abs(m[pivot, col]) > 1e-9))
            {
                return;
            }

            for (var k = 0; k < 12; k++)
            {
                (m[col, k], m[pivot, k]) = (m[pivot, k], m[col, k]);
            }

            var inverse = 1.0 / m[col, col];
            for (var k = 0; k < 12; k++)
            {
                m[col, k] *= inverse;
            }

            for (var row = 0; row < 6; row++)
            {
                if (row != col && m[row, col] != 0.0)
                {
                    var f = m[row, col];
                    for (var k = 0; k < 12; k++)
                    {
                        m[row, k] -= f * m[col, k];
                    }
                }
            }
        }

        foreach (var w in weights)
        {
            w[0] = w[1] = w[2] = 0.0;
        }

        var scale = 1.0 / (size * size);
        for (var i = 0; i < 6; i++)
        {
            var index = particles.IndexOf(points[i]);
            if (index < 0)
            {
                particles.Add(points[i]);
                weights.Add(new double[3]);
                index = particles.Count - 1;
            }

            weights[index][0] = 2.0 * m[0, 6 + i] * scale;
            weights[index][1] = 2.0 * m[2, 6 + i] * scale;
            weights[index][2] = Math.Sqrt(2.0) * m[1, 6 + i] * scale;
        }
    }

    private static void Accumulate(List<int> particles, List<double[]> weights, int particle, double c, double m1, double m2, double m3)
    {
        var index = particles.IndexOf(particle);
        if (index < 0)
        {
            particles.Add(particle);
            weights.Add(new double[3]);
            index = particles.Count - 1;
        }

        weights[index][0] += c * m1;
        weights[index][1] += c * m2;
        weights[index][2] += c * m3;
    }

    private static long EdgeKey(int a, int b) => a < b ? ((long)a << 32) | (uint)b : ((long)b << 32) | (uint)a;

    private static Vector3d Point(double[] x, int i) => new(x[3 * i], x[(3 * i) + 1], x[(3 * i) + 2]);

    private static double Area(double[] x, int a, int b, int c) =>
        0.5 * Vector3d.Cross(Point(x, b) - Point(x, a), Point(x, c) - Point(x, a)).Length;
}
