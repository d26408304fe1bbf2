using System;
using System.Collections.Generic;
using System.Linq;
using ParticlePhysics.Cloth;
using ParticlePhysics.Constraints;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Parallel;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Constraints;

/// <summary>
/// The springs' projection order (<see cref="SpringProjection"/>, <see cref="ConstraintPartition"/>): one group per part,
/// the even parts with their seams, then the odd parts, each group in colour order; every spring once, groups of one
/// phase disjoint, and the plain colour order when there is one part.
/// </summary>
public class ProjectionOrderTests
{
    [Theory]
    [InlineData(32, 4)]
    [InlineData(64, 12)]
    [InlineData(128, 24)]
    public void A_cloth_splits_into_strips_of_at_least_four_rows_in_two_phases(int n, int parts)
    {
        // Strips of at least four rows: a seam reaches two rows into the odd strip below or above it (the bend springs),
        // so no two even strips' seams meet. Two phases: the even strips with their seams, then the odd strips.
        var cloth = ClothOf(n, anchoredEvery: 0);
        var projection = cloth.Projection;
        Assert.Equal(parts, projection.PartCount);
        Assert.Equal(new[] { 0, parts / 2, parts }, projection.PhaseStarts.ToArray());
        Assert.True(n * n / parts >= 4 * n, $"parts of {n * n / parts} particles");
        var seams = CheckInvariants(cloth.Springs, projection, n * n);

        // The seams are the springs across the P - 1 boundaries: 5 n - 2 at the start of a row (n structural, 2 (n - 1)
        // shear, 2 n bend), 3 more within a row (one structural and two bend springs along the row).
        Assert.InRange(seams, (parts - 1) * ((5 * n) - 2), (parts - 1) * ((5 * n) + 1));
    }

    [Fact]
    public void Groups_of_one_phase_share_no_particle_and_anchored_springs_stay_in_their_part()
    {
        // The 64 x 64 cloth with an anchored spring on every third particle (ParallelRunnerTests' cloth).
        var cloth = ClothOf(64, anchoredEvery: 3);
        Assert.Equal(12, cloth.Projection.PartCount);
        CheckInvariants(cloth.Springs, cloth.Projection, 64 * 64);
    }

    [Theory]
    [InlineData(12, 9, 0)]
    [InlineData(12, 9, 2)]
    [InlineData(16, 16, 3)]
    [InlineData(22, 23, 5)]
    public void A_small_world_has_one_part_and_keeps_the_plain_colour_order(int rows, int columns, int anchoredEvery)
    {
        // Fewer than 2 x 256 particles: one part, so the order is exactly the one before parts existed: the greedy
        // colouring in spring order (computed here independently), each colour's pair springs, then its anchored ones.
        var cloth = new ClothBuilder { Rows = rows, Columns = columns }.Build();
        AddAnchored(cloth, anchoredEvery);
        cloth.System.Step(new Xpbd(), 1.0 / 60);
        var projection = cloth.Projection;
        var (order, starts) = PlainColourOrder(cloth.Springs, rows * columns);
        Assert.Equal(1, projection.PartCount);
        Assert.Equal(order, projection.ProjectionOrder.ToArray());
        Assert.Equal(starts, projection.BatchStarts.ToArray());
        Assert.Equal(new[] { 0, order.Length }, projection.GroupStarts.ToArray());
        Assert.Equal(new[] { 0, 1 }, projection.PhaseStarts.ToArray());
        Assert.Equal(starts.Length - 1, projection.ColourCount);
    }

    [Fact]
    public void A_network_whose_index_order_is_not_spatial_falls_back_to_the_plain_colour_order()
    {
        // The 64 x 64 cloth with its particles numbered at random: whatever the split, most springs would be seams.
        var shuffled = ShuffledCloth(64, seed: 13, out var springs, out var projection);
        shuffled.Step(new Xpbd(), 1.0 / 60);
        var (order, starts) = PlainColourOrder(springs, shuffled.Count);
        Assert.Equal(1, projection.PartCount);
        Assert.Equal(order, projection.ProjectionOrder.ToArray());
        Assert.Equal(starts, projection.BatchStarts.ToArray());
    }

    [Theory]
    [InlineData(10, 600)] // parts 0 and 2: a seam between two even parts
    [InlineData(1100, 1792)] // part 4 reaches particle 1792 of part 7, which part 6 reaches too (the link 1791-1792)
    [InlineData(520, 300)] // part 2 reaches particle 300 of part 1, which part 0 reaches too (the spring 255-300)
    public void A_split_whose_groups_would_meet_is_refused_for_fewer_parts(int a, int b)
    {
        // 2048 particles in a chain: 8 parts of 256, whose seams are the 7 links across their boundaries. One more spring
        // (a, b) that would put a particle in two groups of one phase, or a spring in none, rules 8 parts out; 4 parts
        // of 512 take it (it is then inside a part, or a seam from an even part to an odd one that no other seam meets).
        const int particles = 2048;
        var first = Enumerable.Range(0, particles - 1).ToList();
        var second = Enumerable.Range(1, particles - 1).ToList();
        var chain = Partition(first.ToArray(), second.ToArray(), particles);
        Assert.Equal(8, chain.PartCount);
        CheckPartition(first.ToArray(), second.ToArray(), chain, particles);

        // A seam from part 0 to particle 300 of part 1 is fine on its own.
        first.Add(255);
        second.Add(300);
        Assert.Equal(8, Partition(first.ToArray(), second.ToArray(), particles).PartCount);
        first.Add(a);
        second.Add(b);
        var partition = Partition(first.ToArray(), second.ToArray(), particles);
        Assert.Equal(4, partition.PartCount);
        Assert.Equal(new[] { 0, 2, 4 }, partition.PhaseStarts);
        CheckPartition(first.ToArray(), second.ToArray(), partition, particles);
    }

    [Fact]
    public void Each_spring_is_projected_once_in_the_order_stated_on_one_core_and_on_runners()
    {
        // One projection pass against a pass written here: every spring of ProjectionOrder in turn, with the class
        // remarks' formula, operand for operand. Same bits on one core, on two threads and on a scheduler that runs the
        // chunks in reverse order: each spring is projected once, in that order (groups of a phase in any order).
        var cloth = ClothOf(64, anchoredEvery: 3);
        var world = cloth.System;
        StateMetrics.Run(world, new Xpbd(), 1.0 / 60, 5); // a moving, stretched cloth
        var x0 = world.Positions.ToArray();
        var v0 = world.Velocities.ToArray();
        var moved = x0.Select((p, k) => p + (0.004 * Math.Sin(k))).ToArray();
        const double h = 1.0 / 600;
        var expected = (double[])moved.Clone();
        ProjectByHand(cloth.Springs, cloth.Projection.ProjectionOrder.ToArray(), world.InverseMasses.ToArray(), x0, expected, h);

        using var two = new WorkerThreadRunner(2);
        foreach (var runner in new IParallelRunner?[] { null, two, new ReverseRunner() })
        {
            var x = (double[])moved.Clone();
            var v = (double[])v0.Clone();
            var context = new ConstraintContext(
                0, h, x0, v0, x, v, world.Masses, world.InverseMasses, ReadOnlySpan<double>.Empty, runner);
            cloth.Projection.Project(in context);
            Assert.True(StateMetrics.BitHash(expected) == StateMetrics.BitHash(x), $"runner {runner?.GetType().Name ?? "none"}");
        }
    }

    /// <summary>The invariants of a spring projection's order, against the springs themselves; returns the seam count.</summary>
    private static int CheckInvariants(SpringNetwork springs, SpringProjection projection, int particles)
    {
        var (first, second) = Ends(springs);
        return CheckOrder(
            first,
            second,
            particles,
            projection.PartStarts.ToArray(),
            projection.ProjectionOrder.ToArray(),
            projection.GroupStarts.ToArray(),
            projection.PhaseStarts.ToArray(),
            projection.BatchStarts.ToArray());
    }

    private static int CheckPartition(int[] first, int[] second, ConstraintPartition partition, int particles) =>
        CheckOrder(first, second, particles, partition.PartStarts, partition.Order, partition.GroupStarts, partition.PhaseStarts, partition.BatchStarts);

    /// <summary>
    /// Every spring exactly once; groups and batches cut the order into contiguous runs; one group per part, the even
    /// parts (phase 0) then the odd ones (phase 1); a spring of an odd part's group has every end in it, one of an even
    /// part's group every end in it or in an odd part (a seam); the groups of one phase touch no particle in common; no
    /// batch touches a particle twice, and none crosses a group's end. Returns the number of seams.
    /// </summary>
    private static int CheckOrder(
        int[] first, int[] second, int particles, int[] partStarts, int[] order, int[] groupStarts, int[] phaseStarts, int[] batchStarts)
    {
        var count = first.Length;
        Assert.Equal(Enumerable.Range(0, count), order.OrderBy(s => s));
        var parts = partStarts.Length - 1;
        Assert.Equal(0, partStarts[0]);
        Assert.Equal(particles, partStarts[parts]);
        Assert.True(partStarts.Zip(partStarts.Skip(1)).All(p => p.First < p.Second), "parts are non-empty ranges");
        var partOf = new int[particles];
        for (var p = 0; p < parts; p++)
        {
            for (var i = partStarts[p]; i < partStarts[p + 1]; i++)
            {
                partOf[i] = p;
            }
        }

        Assert.Equal(parts + 1, groupStarts.Length);
        Assert.Equal(0, groupStarts[0]);
        Assert.Equal(count, groupStarts[^1]);
        Assert.Equal(parts == 1 ? new[] { 0, 1 } : new[] { 0, parts / 2, parts }, phaseStarts);
        Assert.True(batchStarts.Zip(batchStarts.Skip(1)).All(b => b.First < b.Second), "batches are non-empty");
        Assert.Equal(count, batchStarts[^1]);
        var batchSet = new HashSet<int>(batchStarts);
        Assert.All(groupStarts, g => Assert.Contains(g, batchSet));
        for (var b = 0; b + 1 < batchStarts.Length; b++)
        {
            var seen = new HashSet<int>();
            for (var k = batchStarts[b]; k < batchStarts[b + 1]; k++)
            {
                Assert.True(seen.Add(first[order[k]]) && (second[order[k]] < 0 || seen.Add(second[order[k]])), $"batch {b} touches a particle twice");
            }
        }

        var seams = 0;
        for (var f = 0; f + 1 < phaseStarts.Length; f++)
        {
            var owner = new Dictionary<int, int>();
            for (var g = phaseStarts[f]; g < phaseStarts[f + 1]; g++)
            {
                var part = parts == 1 ? 0 : g < parts / 2 ? 2 * g : (2 * (g - (parts / 2))) + 1;
                for (var k = groupStarts[g]; k < groupStarts[g + 1]; k++)
                {
                    var s = order[k];
                    var ends = second[s] < 0 ? new[] { first[s] } : new[] { first[s], second[s] };
                    Assert.Contains(part, ends.Select(e => partOf[e]));
                    var outside = ends.Where(e => partOf[e] != part).ToArray();
                    Assert.True(outside.Length == 0 || (part % 2 == 0 && outside.All(e => partOf[e] % 2 == 1)), $"spring {s} in part {part}'s group");
                    seams += outside.Length;
                    foreach (var e in ends)
                    {
                        Assert.True(owner.TryAdd(e, g) || owner[e] == g, $"phase {f}: particle {e} is in groups {owner[e]} and {g}");
                    }
                }
            }
        }

        return seams;
    }

    /// <summary>
    /// The order before parts: each spring (pairs, then anchored) takes the smallest colour that no earlier spring at its
    /// particles has; by colour, each colour's pairs then its anchored springs, in index order. And the colours' starts.
    /// </summary>
    private static (int[] Order, int[] Starts) PlainColourOrder(SpringNetwork springs, int particles)
    {
        var (first, second) = Ends(springs);
        var count = first.Length;
        var coloursAt = Enumerable.Range(0, particles).Select(_ => new HashSet<int>()).ToArray();
        var colour = new int[count];
        for (var s = 0; s < count; s++)
        {
            var k = 0;
            while (coloursAt[first[s]].Contains(k) || (second[s] >= 0 && coloursAt[second[s]].Contains(k)))
            {
                k++;
            }

            colour[s] = k;
            coloursAt[first[s]].Add(k);
            if (second[s] >= 0)
            {
                coloursAt[second[s]].Add(k);
            }
        }

        var order = Enumerable.Range(0, count).OrderBy(s => colour[s]).ThenBy(s => second[s] < 0 ? 1 : 0).ThenBy(s => s).ToArray();
        var colours = count == 0 ? 0 : colour.Max() + 1;
        var starts = Enumerable.Range(0, colours + 1).Select(c => colour.Count(k => k < c)).ToArray();
        return (order, starts);
    }

    /// <summary>The springs' ends in the projection's indexing: the pair springs, then the anchored ones (second end -1).</summary>
    private static (int[] First, int[] Second) Ends(SpringNetwork springs)
    {
        ISpringElements elements = springs;
        int pairs = elements.PairCount, anchored = elements.AnchoredCount;
        var first = new int[pairs + anchored];
        var second = new int[pairs + anchored];
        elements.CopyPairs(first, second, new double[3 * pairs]);
        var particle = new int[anchored];
        elements.CopyAnchored(particle, new double[6 * anchored]);
        for (var a = 0; a < anchored; a++)
        {
            first[pairs + a] = particle[a];
            second[pairs + a] = -1;
        }

        return (first, second);
    }

    /// <summary>
    /// One projection pass in <paramref name="order"/>, written from SpringProjection's remarks: k h^2 and c h, then per
    /// spring dlambda = -(k h^2 C + c h u . ((x_i - x0_i) - (x_j - x0_j))) / ((k h^2 + c h) w + 1).
    /// </summary>
    private static void ProjectByHand(SpringNetwork springs, int[] order, double[] w, double[] x0, double[] x, double h)
    {
        ISpringElements elements = springs;
        int pairs = elements.PairCount, anchored = elements.AnchoredCount;
        var first = new int[pairs];
        var second = new int[pairs];
        var parameters = new double[3 * pairs];
        elements.CopyPairs(first, second, parameters);
        var particle = new int[anchored];
        var anchors = new double[6 * anchored];
        elements.CopyAnchored(particle, anchors);
        foreach (var s in order)
        {
            int i, j;
            double k, rest, c, wj, ax, ay, az;
            if (s < pairs)
            {
                (i, j, k, rest, c) = (first[s], second[s], parameters[3 * s], parameters[(3 * s) + 1], parameters[(3 * s) + 2]);
                (wj, ax, ay, az) = (w[j], x[3 * j], x[(3 * j) + 1], x[(3 * j) + 2]);
            }
            else
            {
                var a = s - pairs;
                (i, j, k, rest, c) = (particle[a], -1, anchors[(6 * a) + 3], anchors[(6 * a) + 4], anchors[(6 * a) + 5]);
                (wj, ax, ay, az) = (0.0, anchors[6 * a], anchors[(6 * a) + 1], anchors[(6 * a) + 2]);
            }

            double stiffness = k * (h * h), damping = c * h, wi = w[i], wsum = wi + wj;
            if (wsum == 0.0)
            {
                continue;
            }

            double dx = x[3 * i] - ax, dy = x[(3 * i) + 1] - ay, dz = x[(3 * i) + 2] - az;
            double mx = x[3 * i] - x0[3 * i], my = x[(3 * i) + 1] - x0[(3 * i) + 1], mz = x[(3 * i) + 2] - x0[(3 * i) + 2];
            if (j >= 0)
            {
                mx -= x[3 * j] - x0[3 * j];
                my -= x[(3 * j) + 1] - x0[(3 * j) + 1];
                mz -= x[(3 * j) + 2] - x0[(3 * j) + 2];
            }

            var squared = (dx * dx) + (dy * dy) + (dz * dz);
            if (squared == 0.0)
            {
                continue;
            }

            var l = Math.Sqrt(squared);
            var inverse = 1.0 / l;
            double ux = dx * inverse, uy = dy * inverse, uz = dz * inverse;
            var along = (ux * mx) + (uy * my) + (uz * mz);
            var dlambda = -((stiffness * (l - rest)) + (damping * along)) / (((stiffness + damping) * wsum) + 1.0);
            double cx = dlambda * ux, cy = dlambda * uy, cz = dlambda * uz;
            x[3 * i] += wi * cx;
            x[(3 * i) + 1] += wi * cy;
            x[(3 * i) + 2] += wi * cz;
            if (j >= 0)
            {
                x[3 * j] -= wj * cx;
                x[(3 * j) + 1] -= wj * cy;
                x[(3 * j) + 2] -= wj * cz;
            }
        }
    }

    /// <summary>The n x n course cloth, projected once (so that its order is computed), with anchored springs if asked.</summary>
    private static ParticleCloth ClothOf(int n, int anchoredEvery)
    {
        var cloth = new ClothScenario { Resolution = 1.0 / (n - 1) }.CreateBuilder().Build();
        AddAnchored(cloth, anchoredEvery);
        cloth.System.Step(new Xpbd(), 1.0 / 60);
        return cloth;
    }

    private static void AddAnchored(ParticleCloth cloth, int every)
    {
        for (var i = every - 1; every > 0 && i < cloth.System.Count; i += every)
        {
            var p = cloth.System.GetPosition(i);
            cloth.Springs.AddAnchored(i, new Vector3d(p.X, 0.1, p.Z), 5, 0.1, 0.01);
        }
    }

    /// <summary>The n x n cloth's particles and springs, with the particles numbered in a random order.</summary>
    private static ParticleWorld ShuffledCloth(int n, ulong seed, out SpringNetwork springs, out SpringProjection projection)
    {
        var cloth = new ClothScenario { Resolution = 1.0 / (n - 1) }.CreateBuilder().Build();
        var random = new SeededRandom(seed);
        var index = Enumerable.Range(0, n * n).ToArray();
        for (var i = index.Length - 1; i > 0; i--)
        {
            var j = random.Next(i + 1);
            (index[i], index[j]) = (index[j], index[i]);
        }

        var world = new ParticleWorld();
        var byNewIndex = new int[n * n];
        for (var i = 0; i < n * n; i++)
        {
            byNewIndex[index[i]] = i;
        }

        foreach (var old in byNewIndex)
        {
            world.AddParticle(cloth.System.GetPosition(old), cloth.System.Masses[old]);
        }

        springs = new SpringNetwork(world);
        for (var s = 0; s < cloth.Springs.Count; s++)
        {
            var (a, b) = cloth.Springs.GetEnds(s);
            springs.Add(index[a], index[b], 50, 0.1, 0.05);
        }

        world.AddForce(springs);
        projection = new SpringProjection(springs);
        world.AddConstraints(projection);
        return world;
    }

    private static ConstraintPartition Partition(int[] first, int[] second, int particles)
    {
        var order = new int[first.Length];
        var starts = ConstraintColouring.Colour(first, second, first.Length, particles, order);
        return ConstraintPartition.Build(first, second, first.Length, particles, order, starts);
    }

    /// <summary>A scheduler that runs the chunks one at a time, last first, on the calling thread.</summary>
    private sealed class ReverseRunner : IParallelRunner
    {
        public int MaxParallelism => 3;

        public void Run(IParallelWork work, int chunkCount)
        {
            for (var chunk = chunkCount - 1; chunk >= 0; chunk--)
            {
                work.Execute(chunk, chunkCount);
            }
        }
    }
}
