using System;
using ParticlePhysics.Forces;

namespace ParticlePhysics.Cloth;

/// <summary>
/// Euler-Bernoulli bending of rigidity EI along a polyline, as elements of a <see cref="QuadraticBending"/>: one per
/// interior point, its curvature the second difference of the positions.
/// </summary>
/// <remarks>
/// A beam bent by w(s) stores (EI / 2) integral w''^2 ds; for inextensible bending of a straight rope, x(s) with |x'| = 1,
/// |x''| is the curvature, and (EI / 2) integral |x''|^2 ds is the energy whatever the rotation. At point i, between
/// segments of rest lengths l0 (before) and l1 (after): kappa_i = (2 / (l0 + l1)) ((x_(i+1) - x_i) / l1 -
/// (x_i - x_(i-1)) / l0), the second difference (exact for quadratics on any spacing), with weight (l0 + l1) / 2 in
/// the integral: element weights b = (2 / (l0 + l1)) (1 / l0, -(1 / l0 + 1 / l1), 1 / l1), stiffness
/// s = EI (l0 + l1) / 2. The ends carry no element: a free end carries no moment. Zero for any straight uniform motion,
/// so rigid motions of the straight rope cost nothing; the rest shape is straight. A cantilever clamped by pinning its
/// first two points then sags mu g L^4 / (8 EI) to second order in the spacing, with L measured from midway between
/// them (where the discrete slope is held).
/// </remarks>
public static class RopeBending
{
    /// <summary>
    /// Adds the elements of a polyline of particles <paramref name="firstParticle"/> + 0, 1, ..., whose rest positions
    /// are <paramref name="restPoints"/> (3 values per point, at least 3 points for any element).
    /// </summary>
    /// <param name="bending">The energy to add to.</param>
    /// <param name="restPoints">x, y, z of each point at rest; consecutive points distinct.</param>
    /// <param name="firstParticle">The world's index of point 0.</param>
    /// <param name="rigidity">EI, in N m^2: finite and &gt;= 0.</param>
    /// <returns>The number of elements added (points - 2, or 0).</returns>
    public static int AddPolyline(QuadraticBending bending, ReadOnlySpan<double> restPoints, int firstParticle, double rigidity)
    {
        Guard.NotNull(bending, nameof(bending));
        Guard.NonNegativeFinite(rigidity, nameof(rigidity));
        var x = restPoints.ToArray();
        var points = x.Length / 3;
        Span<int> particles = stackalloc int[3];
        Span<double> weights = stackalloc double[3];
        for (var i = 1; i + 1 < points; i++)
        {
            var l0 = Distance(x, i - 1, i);
            var l1 = Distance(x, i, i + 1);
            if (!(l0 > 0) || !(l1 > 0))
            {
                throw new ArgumentException($"Points {i - 1}, {i} and {i + 1} of the rope: consecutive points must be distinct.", nameof(restPoints));
            }

            var scale = 2.0 / (l0 + l1);
            particles[0] = firstParticle + i - 1;
            particles[1] = firstParticle + i;
            particles[2] = firstParticle + i + 1;
            weights[0] = scale / l0;
            weights[1] = -scale * ((1.0 / l0) + (1.0 / l1));
            weights[2] = scale / l1;
            bending.Add(particles, weights, rigidity * 0.5 * (l0 + l1));
        }

        return Math.Max(0, points - 2);
    }

    private static double Distance(double[] x, int a, int b)
    {
        double dx = x[3 * a] - x[3 * b], dy = x[(3 * a) + 1] - x[(3 * b) + 1], dz = x[(3 * a) + 2] - x[(3 * b) + 2];
        return Math.Sqrt((dx * dx) + (dy * dy) + (dz * dz));
    }
}
