using System;

namespace ParticlePhysics.Fluids;

/// <summary>
/// What walls add to the density of a fluid particle near them, and to its constraint gradient: each wall is taken as
/// the plane tangent to it, with the half-space behind filled by the fluid's rest lattice, still and with no
/// constraint of its own, its first layer s / 2 behind the surface and aligned with the particle along the wall (the
/// wall weight of Harada, Koshizuka and Kawaguchi, "Smoothed particle hydrodynamics on GPUs", 2007, summed over the
/// lattice). A particle of the rest lattice against the walls it was cut from is then at rho_0 exactly, as inside.
/// </summary>
/// <remarks>
/// <para>
/// A particle next to a wall misses the neighbours beyond it; without this term it is pulled in until its own
/// estimate reaches rho_0, and a column settles low by the layers next to its walls. A ghost at o from the particle (at depth
/// z = d + s / 2 + l s behind the wall, l = 0, 1, ..., and lateral offset (i t + j b) s in the wall's frame) counts as a
/// fluid neighbour does: m W(|o|) in the density sum and the spiky gradient m f(|o|) o in the gradient sum. As the
/// particle moves towards the wall the lattice comes with the wall, so the density grows as it does when two fluid
/// particles meet, and the projection treats walls and fluid alike. A particle inside a wall (d &lt; 0) counts as if
/// on its surface: the contact stage, not the density, pushes it out.
/// </para>
/// <para>
/// Where two walls meet, their half-spaces overlap in the corner, whose ghosts would count twice. So the ghosts of
/// each wall are weighted by prod (1 - S(u_B)) over the walls B before it, u_B = clamp(1/2 - phi_B / s, 0, 1) from
/// the ghost's signed distance phi_B to B, and S(u) = u^2 (3 - 2 u): a ghost half a spacing inside an earlier wall is
/// left out, one half a spacing outside is kept, and S's zero slope at both ends keeps the density's derivative that
/// of the ghosts at rest.
/// </para>
/// </remarks>
internal sealed class FluidWall
{
    /// <summary>The values a wall's frame takes in <see cref="Add"/>'s frames: n, then t and b along the wall.</summary>
    public const int FrameLength = 9;

    private readonly SphKernel _kernel;
    private readonly double _spacing;
    private readonly double _mass;
    private readonly int _reach;

    public FluidWall(SphKernel kernel, double spacing, double mass)
    {
        _kernel = kernel;
        _spacing = spacing;
        _mass = mass;
        _reach = (int)(kernel.Radius / spacing);
    }

    /// <summary>
    /// The distance from a wall within which it matters to a particle: its ghosts reach the kernel within h - s / 2,
    /// and it takes ghosts of the other walls out within h + s / 2.
    /// </summary>
    public double Reach => _kernel.Radius + (0.5 * _spacing);

    /// <summary>
    /// Adds to <paramref name="gradient"/> (3 values from <paramref name="at"/>) the walls' share of
    /// sum_b m_b grad_a W_ab, and returns their share of sum_b m_b W_ab (kg/m^3, before kappa), for a particle at
    /// signed distances <paramref name="distances"/> from the walls whose frames are in <paramref name="frames"/>,
    /// <paramref name="count"/> of them from <paramref name="first"/> on.
    /// </summary>
    public double Add(double[] distances, double[] frames, int first, int count, double[] gradient, int at)
    {
        var h = _kernel.Radius;
        var h2 = h * h;
        var s = _spacing;
        var inverse = 1.0 / s;
        double density = 0.0, gx = 0.0, gy = 0.0, gz = 0.0;
        for (var a = first; a < first + count; a++)
        {
            var f = FrameLength * a;
            double nx = frames[f], ny = frames[f + 1], nz = frames[f + 2];
            double tx = frames[f + 3], ty = frames[f + 4], tz = frames[f + 5];
            double bx = frames[f + 6], by = frames[f + 7], bz = frames[f + 8];
            var start = distances[a] > 0.0 ? distances[a] : 0.0;
            for (var z = start + (0.5 * s); z < h; z += s)
            {
                for (var j = -_reach; j <= _reach; j++)
                {
                    for (var i = -_reach; i <= _reach; i++)
                    {
                        double u = i * s, v = j * s;
                        var r2 = (z * z) + (u * u) + (v * v);
                        if (r2 >= h2)
                        {
                            continue;
                        }

                        double ox = (u * tx) + (v * bx) - (z * nx), oy = (u * ty) + (v * by) - (z * ny), oz = (u * tz) + (v * bz) - (z * nz);
                        var weight = 1.0;
                        for (var b = first; b < a && weight > 0.0; b++)
                        {
                            var e = FrameLength * b;
                            var phi = distances[b] + (frames[e] * ox) + (frames[e + 1] * oy) + (frames[e + 2] * oz);
                            var depth = 0.5 - (phi * inverse);
                            if (depth > 0.0)
                            {
                                depth = depth < 1.0 ? depth : 1.0;
                                weight *= 1.0 - (depth * depth * (3.0 - (2.0 * depth)));
                            }
                        }

                        if (!(weight > 0.0))
                        {
                            continue;
                        }

                        var r = Math.Sqrt(r2);
                        density += weight * _kernel.Density(r);
                        var g = weight * _kernel.GradientOverDistance(r);
                        gx += g * ox;
                        gy += g * oy;
                        gz += g * oz;
                    }
                }
            }
        }

        gradient[at] += _mass * gx;
        gradient[at + 1] += _mass * gy;
        gradient[at + 2] += _mass * gz;
        return _mass * density;
    }
}
