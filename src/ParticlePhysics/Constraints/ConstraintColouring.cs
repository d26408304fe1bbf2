using System;

namespace ParticlePhysics.Constraints;

/// <summary>
/// Greedy colouring of two-particle constraints (springs, rods) so that no two constraints of one colour share a
/// particle: the projections of one colour are independent of each other (they could run in parallel, and their
/// order within the colour does not change the result), and a projection pass in colour order does not wait on the one
/// before it. Computed once when the topology changes, never per step.
/// </summary>
/// <remarks>
/// Each constraint, in index order, takes the smallest colour that none of the constraints already coloured at its
/// particles has (greedy colouring of the line graph: with d the most constraints at one particle, each constraint
/// meets at most 2 (d - 1) others, so at most 2 d - 1 colours). An anchored constraint (second end -1) touches one
/// particle.
/// </remarks>
internal static class ConstraintColouring
{
    /// <summary>
    /// Fills <paramref name="order"/> with the constraints 0 .. count - 1 sorted by colour (stable: index order within a
    /// colour) and returns the start of each colour in it, with one last entry equal to <paramref name="count"/>.
    /// </summary>
    public static int[] Colour(int[] first, int[] second, int count, int particleCount, int[] order)
    {
        // Constraints by particle (compressed rows), to find the colours already taken at each end.
        var start = new int[particleCount + 1];
        for (var c = 0; c < count; c++)
        {
            start[first[c] + 1]++;
            if (second[c] >= 0)
            {
                start[second[c] + 1]++;
            }
        }

        for (var p = 0; p < particleCount; p++)
        {
            start[p + 1] += start[p];
        }

        var fill = new int[particleCount];
        var at = new int[start[particleCount]];
        for (var c = 0; c < count; c++)
        {
            at[start[first[c]] + fill[first[c]]++] = c;
            if (second[c] >= 0)
            {
                at[start[second[c]] + fill[second[c]]++] = c;
            }
        }

        var colour = new int[count];
        var taken = new int[count + 1]; // taken[k] == c + 1: colour k is used next to constraint c
        var colours = 0;
        for (var c = 0; c < count; c++)
        {
            Mark(first[c], c);
            if (second[c] >= 0)
            {
                Mark(second[c], c);
            }

            var k = 0;
            while (taken[k] == c + 1)
            {
                k++;
            }

            colour[c] = k;
            colours = Math.Max(colours, k + 1);
        }

        // Counting sort by colour, stable.
        var starts = new int[colours + 1];
        for (var c = 0; c < count; c++)
        {
            starts[colour[c] + 1]++;
        }

        for (var k = 0; k < colours; k++)
        {
            starts[k + 1] += starts[k];
        }

        var next = new int[colours];
        for (var c = 0; c < count; c++)
        {
            order[starts[colour[c]] + next[colour[c]]++] = c;
        }

        return starts;

        void Mark(int particle, int constraint)
        {
            for (var a = start[particle]; a < start[particle + 1]; a++)
            {
                var other = at[a];
                if (other < constraint)
                {
                    taken[colour[other]] = constraint + 1;
                }
            }
        }
    }
}
