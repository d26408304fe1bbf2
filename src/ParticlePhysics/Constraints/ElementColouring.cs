using System;

namespace ParticlePhysics.Constraints;

/// <summary>
/// Greedy colouring of constraints of several particles each (a membrane's triangles, a bending energy's stencils), so
/// that no two constraints of one colour share a particle: the projections of a colour are independent, and their order
/// within it changes no bit. <see cref="ConstraintColouring"/> does the same for two-particle constraints. Computed once
/// when the topology changes, never per step.
/// </summary>
/// <remarks>
/// Each constraint, in index order, takes the smallest colour that no constraint already coloured at any of its
/// particles has; a constraint of m particles that each meet at most d constraints meets at most m (d - 1) others, so at
/// most m (d - 1) + 1 colours.
/// </remarks>
internal static class ElementColouring
{
    /// <summary>
    /// Fills <paramref name="order"/> with the constraints 0 .. count - 1 sorted by colour (stable: index order within a
    /// colour) and returns the start of each colour in it, with one last entry equal to <paramref name="count"/>.
    /// </summary>
    /// <param name="particles"><paramref name="stride"/> slots per constraint, -1 for an unused slot.</param>
    /// <param name="stride">Particle slots per constraint.</param>
    /// <param name="count">The number of constraints.</param>
    /// <param name="particleCount">The number of particles: every used slot is below it.</param>
    /// <param name="order">Receives the constraints in colour order; at least <paramref name="count"/> long.</param>
    public static int[] Colour(int[] particles, int stride, int count, int particleCount, int[] order)
    {
        var start = new int[particleCount + 1];
        for (var k = 0; k < stride * count; k++)
        {
            if (particles[k] >= 0)
            {
                start[particles[k] + 1]++;
            }
        }

        for (var p = 0; p < particleCount; p++)
        {
            start[p + 1] += start[p];
        }

        var fill = new int[particleCount];
        var at = new int[start[particleCount]];
        for (var k = 0; k < stride * count; k++)
        {
            var p = particles[k];
            if (p >= 0)
            {
                at[start[p] + fill[p]++] = k / stride;
            }
        }

        var colour = new int[count];
        var taken = new int[count + 1]; // taken[c] == e + 1: colour c is used next to constraint e
        var colours = 0;
        for (var e = 0; e < count; e++)
        {
            for (var v = 0; v < stride; v++)
            {
                var p = particles[(stride * e) + v];
                if (p < 0)
                {
                    continue;
                }

                for (var a = start[p]; a < start[p + 1]; a++)
                {
                    var other = at[a];
                    if (other < e)
                    {
                        taken[colour[other]] = e + 1;
                    }
                }
            }

            var c = 0;
            while (taken[c] == e + 1)
            {
                c++;
            }

            colour[e] = c;
            colours = Math.Max(colours, c + 1);
        }

        var starts = new int[colours + 1];
        for (var e = 0; e < count; e++)
        {
            starts[colour[e] + 1]++;
        }

        for (var c = 0; c < colours; c++)
        {
            starts[c + 1] += starts[c];
        }

        var next = new int[colours];
        for (var e = 0; e < count; e++)
        {
            order[starts[colour[e]] + next[colour[e]]++] = e;
        }

        return starts;
    }
}
