using System;
using System.Runtime.InteropServices;

namespace ParticlePhysics.Constraints;

// Under xpbd: each rod projected once per substep with compliance 0, in colour order.
public sealed partial class RodNetwork
{
    /// <inheritdoc />
    public void Project(in ConstraintContext context)
    {
        if (_count == 0)
        {
            return;
        }

        EnsureTopology(context.Count);
        unsafe
        {
            fixed (double* x = context.Positions, w = &MemoryMarshal.GetReference(context.InverseMasses))
            fixed (double* anchor = _anchor, length = _length)
            fixed (int* first = _first, second = _second, order = _order)
            fixed (bool* cable = _cable)
            {
                for (var c = 0; c < _count; c++)
                {
                    var r = order[c];
                    long i = 3 * first[r];
                    var b = second[r];
                    var wi = w[first[r]];
                    var wj = b >= 0 ? w[b] : 0.0;
                    var wsum = wi + wj;
                    if (wsum == 0.0)
                    {
                        continue;
                    }

                    var pb = b >= 0 ? x + (3L * b) : anchor + (3L * r);
                    double dx = x[i] - pb[0], dy = x[i + 1] - pb[1], dz = x[i + 2] - pb[2];
                    var squared = (dx * dx) + (dy * dy) + (dz * dz);
                    if (squared == 0.0)
                    {
                        continue;
                    }

                    var l = Math.Sqrt(squared);
                    var violation = l - length[r];
                    if (cable[r] && violation <= 0.0)
                    {
                        continue;
                    }

                    // Compliance 0: dlambda = -C / (w_i + w_j), along u = d / l.
                    var scale = -violation / (wsum * l);
                    double cx = scale * dx, cy = scale * dy, cz = scale * dz;
                    x[i] += wi * cx;
                    x[i + 1] += wi * cy;
                    x[i + 2] += wi * cz;
                    if (b >= 0)
                    {
                        pb[0] -= wj * cx;
                        pb[1] -= wj * cy;
                        pb[2] -= wj * cz;
                    }
                }
            }
        }
    }

    /// <inheritdoc />
    /// <remarks>Nothing: the velocities taken from the change of positions already carry the rods and cables.</remarks>
    public void SolveVelocities(in ConstraintContext context)
    {
    }
}
