using System;

namespace ParticlePhysics.Constraints;

/// <summary>
/// A projection order of two-particle constraints with few synchronisation points, the same whatever runs it: the
/// particles split into <see cref="PartCount"/> parts (contiguous index ranges, a function of the particle count and
/// the topology only, never of the runner), one group of constraints per part, in two phases: first the even parts
/// (0, 2, 4, ...), each with its interior (its constraints with every end in it) and the seams it shares with its odd
/// neighbours (the constraints with one end in it and one in an odd part), then the odd parts' interiors. Groups of
/// one phase share no particle, so each phase is one hand-off to a runner, and one core runs the same groups one
/// after the other: the same operations, the same bits. Computed once when the topology changes, never per step.
/// </summary>
/// <remarks>
/// <para>
/// Within each group the constraints keep the colour order (<see cref="ConstraintColouring"/>, restricted to the
/// group), as a list of batches, one per colour present; the projection of one batch does not depend on the order
/// inside it. A seam is projected with the even part it belongs to, in colour order among that part's own
/// constraints, as the plain colour order would. That keeps the cloth as smooth as the plain colour order does;
/// projecting all the seams after all the interiors instead leaves the springs across each boundary compressed between
/// stretched rows.
/// </para>
/// <para>
/// Phase 0's groups share no particle when every seam joins an even part and an odd one and no particle of an odd
/// part is reached by the seams of two even parts. On the cloth, whose particles are row-major, parts are strips of
/// rows and a seam reaches two rows into its odd neighbour (the bend springs): strips of at least four rows suffice.
/// Choosing P: the largest of <see cref="PartCandidates"/> whose parts hold at least
/// <see cref="MinParticlesPerPart"/> particles, whose seams are at most a quarter of the constraints, and whose
/// phase 0 is disjoint. Each phase has P / 2 groups, a divisor of 12, and a runner gets whole groups: 12 groups
/// (P = 24) are shared evenly by 2, 3, 4 and 6 cores, 6 by 2, 3 and 6, 4 by 2 and 4; 5, 7 or 8 cores wait for at most
/// one group more than the others. The cloth gets P = 4 at 32 x 32, 12 at 64 x 64 (strips of 5 1/3 rows), 24 from
/// 96 x 96 up. When no candidate passes (fewer than 4 x 256 particles, or a network whose index order is not
/// spatial, where most constraints would be seams) P = 1: one group, its batches the plain colours, which is the
/// colour order itself.
/// </para>
/// </remarks>
internal sealed class ConstraintPartition
{
    /// <summary>The part counts tried, largest first: even, so that both phases have P / 2 groups.</summary>
    public static readonly int[] PartCandidates = { 24, 12, 8, 4 };

    /// <summary>The fewest particles in a part: smaller parts are not worth a chunk of their own.</summary>
    public const int MinParticlesPerPart = 256;

    // Seams may be at most 1 / MaxSeamShareDivisor of the constraints: phase 0's groups carry them, so that bounds how
    // much heavier they are than phase 1's.
    private const int MaxSeamShareDivisor = 4;

    private ConstraintPartition(
        int[] partStarts, int[] order, int[] groupStarts, int[] phaseStarts, int[] batchStarts, int[] groupBatchStarts)
    {
        PartStarts = partStarts;
        Order = order;
        GroupStarts = groupStarts;
        PhaseStarts = phaseStarts;
        BatchStarts = batchStarts;
        GroupBatchStarts = groupBatchStarts;
    }

    /// <summary>The number of parts P.</summary>
    public int PartCount => PartStarts.Length - 1;

    /// <summary>Part p is the particles [PartStarts[p], PartStarts[p + 1]); P + 1 entries.</summary>
    public int[] PartStarts { get; }

    /// <summary>The constraints in projection order: group by group, and within a group batch by batch.</summary>
    public int[] Order { get; }

    /// <summary>
    /// Where each group starts in <see cref="Order"/>, with a last entry equal to the constraint count: one group per
    /// part, the even parts first (group g &lt; P / 2 is part 2 g, with its seams), then the odd ones (group P / 2 + g
    /// is part 2 g + 1). With one part, one group.
    /// </summary>
    public int[] GroupStarts { get; }

    /// <summary>
    /// Where each phase starts among the groups, with a last entry equal to the group count: { 0, P / 2, P }, or
    /// { 0, 1 } with one part. The groups of one phase share no particle.
    /// </summary>
    public int[] PhaseStarts { get; }

    /// <summary>
    /// Where each batch starts in <see cref="Order"/>, with a last entry equal to the constraint count: a batch is the
    /// constraints of one colour within one group, so no two of them share a particle.
    /// </summary>
    public int[] BatchStarts { get; }

    /// <summary>Where each group's batches start among the batches, with a last entry equal to the batch count.</summary>
    public int[] GroupBatchStarts { get; }

    /// <summary>
    /// The partition of constraints 0 .. count - 1 (ends <paramref name="first"/>, <paramref name="second"/>, -1 for a
    /// constraint on one particle) given their colour order: <paramref name="byColour"/>, the constraints sorted by
    /// colour (any order within a colour, which is kept), and <paramref name="colourStarts"/> where each colour starts.
    /// </summary>
    public static ConstraintPartition Build(
        int[] first, int[] second, int count, int particleCount, int[] byColour, int[] colourStarts)
    {
        var colourOf = new int[count];
        for (var c = 0; c + 1 < colourStarts.Length; c++)
        {
            for (var k = colourStarts[c]; k < colourStarts[c + 1]; k++)
            {
                colourOf[byColour[k]] = c;
            }
        }

        foreach (var parts in PartCandidates)
        {
            if (particleCount / parts >= MinParticlesPerPart
                && TryBuild(first, second, count, particleCount, byColour, colourOf, parts) is { } partition)
            {
                return partition;
            }
        }

        // One part: its interior is every constraint, its batches the colours.
        return new ConstraintPartition(
            new[] { 0, particleCount },
            (int[])byColour.Clone(),
            new[] { 0, count },
            new[] { 0, 1 },
            (int[])colourStarts.Clone(),
            new[] { 0, colourStarts.Length - 1 });
    }

    /// <summary>
    /// The partition into <paramref name="parts"/> (even) parts, or null if a seam spring joins two parts of the same
    /// parity, seams are more than a quarter of the constraints, or two even parts' seams reach one particle.
    /// </summary>
    private static ConstraintPartition? TryBuild(
        int[] first, int[] second, int count, int particleCount, int[] byColour, int[] colourOf, int parts)
    {
        // Contiguous, as even as integers allow; partOf[i] is particle i's part.
        var partStarts = new int[parts + 1];
        var partOf = new int[particleCount];
        for (var p = 0; p < parts; p++)
        {
            partStarts[p + 1] = (int)((long)particleCount * (p + 1) / parts);
            for (var i = partStarts[p]; i < partStarts[p + 1]; i++)
            {
                partOf[i] = p;
            }
        }

        // Each constraint's part: its ends' part, or for a seam the even one of its two parts. reachedBy[i]: the even
        // part whose seams reach particle i of an odd part (-1: none yet); two would put one particle in two groups of
        // phase 0.
        var partOfConstraint = new int[count];
        var reachedBy = new int[particleCount];
        reachedBy.AsSpan().Fill(-1);
        var seams = 0;
        for (var c = 0; c < count; c++)
        {
            int a = partOf[first[c]], b = second[c] >= 0 ? partOf[second[c]] : a;
            if (a == b)
            {
                partOfConstraint[c] = a;
                continue;
            }

            if (((a ^ b) & 1) == 0)
            {
                return null;
            }

            var (even, oddEnd) = (a & 1) == 0 ? (a, second[c]) : (b, first[c]);
            if (reachedBy[oddEnd] >= 0 && reachedBy[oddEnd] != even)
            {
                return null;
            }

            reachedBy[oddEnd] = even;
            partOfConstraint[c] = even;
            seams++;
        }

        if ((long)seams * MaxSeamShareDivisor > count)
        {
            return null;
        }

        // Groups by phase: the even parts 0, 2, 4, ... (with their seams), then the odd parts 1, 3, 5, ...; the colour
        // order distributed over them, stably, so that each group is in colour order and its colours are its batches.
        var half = parts / 2;
        var groupStarts = new int[parts + 1];
        for (var c = 0; c < count; c++)
        {
            groupStarts[GroupOf(partOfConstraint[c], half) + 1]++;
        }

        for (var g = 0; g < parts; g++)
        {
            groupStarts[g + 1] += groupStarts[g];
        }

        var order = new int[count];
        var next = (int[])groupStarts.Clone();
        for (var k = 0; k < count; k++)
        {
            var c = byColour[k];
            order[next[GroupOf(partOfConstraint[c], half)]++] = c;
        }

        var batchStarts = new int[count + 1];
        var groupBatchStarts = new int[parts + 1];
        var batches = 0;
        for (var g = 0; g < parts; g++)
        {
            groupBatchStarts[g] = batches;
            for (var k = groupStarts[g]; k < groupStarts[g + 1]; k++)
            {
                if (k == groupStarts[g] || colourOf[order[k]] != colourOf[order[k - 1]])
                {
                    batchStarts[batches++] = k;
                }
            }
        }

        groupBatchStarts[parts] = batches;
        batchStarts[batches] = count;
        Array.Resize(ref batchStarts, batches + 1);
        return new ConstraintPartition(partStarts, order, groupStarts, new[] { 0, half, parts }, batchStarts, groupBatchStarts);
    }

    /// <summary>The group of part p: the even parts first (phase 0), then the odd ones (phase 1).</summary>
    private static int GroupOf(int part, int half) => (part & 1) == 0 ? part / 2 : half + (part / 2);
}
