using System;
using System.Collections.Generic;
using System.Linq;
using ParticlePhysics.Contacts;

namespace ParticlePhysics.Tests.Contacts;

/// <summary>The spatial hash finds exactly the overlapping pairs that brute force finds.</summary>
public class BroadPhaseTests
{
    [Theory]
    [InlineData(1, 0.1, 0, true)]
    [InlineData(500, 0.05, 0, false)]
    [InlineData(2000, 0.02, 5, false)]
    [InlineData(3000, 0.2, 40, true)]
    public void The_grid_finds_exactly_the_pairs_brute_force_finds(int count, double size, int large, bool dense)
    {
        var state = (uint)(count + 17);
        var min = new double[3 * count];
        var max = new double[3 * count];
        for (var i = 0; i < count; i++)
        {
            // Boxes of varied size in a unit cube, some clustered on one point, a few very large (fast particles).
            var extent = size * (0.2 + Math.Abs(ObstacleTests.Next(ref state)));
            if (i < large)
            {
                extent *= 30;
            }

            for (var c = 0; c < 3; c++)
            {
                var centre = i % 7 == 0 ? 0.5 : ObstacleTests.Next(ref state);
                min[(3 * i) + c] = centre - (0.5 * extent);
                max[(3 * i) + c] = centre + (0.5 * extent);
            }
        }

        var grid = new SpatialHashGrid();
        grid.FindPairs(min, max, count);
        Assert.Equal(dense, grid.Dense); // both tables: a dense box of cells, and a hash when the cells are spread thinly
        var found = new HashSet<(int, int)>();
        for (var p = 0; p < grid.PairCount; p++)
        {
            Assert.True(grid.First[p] < grid.Second[p]);
            Assert.True(found.Add((grid.First[p], grid.Second[p])), $"pair {grid.First[p]}, {grid.Second[p]} twice");
        }

        var brute = BruteForce(min, max, count);
        Assert.Equal(brute.Count, found.Count);
        Assert.True(brute.SetEquals(found));
    }

    [Fact]
    public void A_dense_table_lists_each_boxs_pairs_close_together_wherever_the_boxes_are_stored()
    {
        // A pile of 20 x 3 x 20 overlapping boxes (18 x 2 x 18 cells) stored in a shuffled order. In the order of the
        // cells a box's pairs all come within one slab of the slowest axis and a few cells (about 1 / 18 of the list;
        // at most 3 / 18 here); in index order (the hashed table's, forced by one far box that touches nothing) they
        // spread over the whole list.
        var (min, max) = ShuffledLattice(20, 3, 20, out var count);
        var grid = new SpatialHashGrid();
        grid.FindPairs(min, max, count);
        Assert.True(grid.Dense);
        var dense = Pairs(grid);
        var window = WidestWindow(grid, count);
        Assert.True(window <= 3 * grid.PairCount / 18, $"a box's pairs span {window} of {grid.PairCount} places");

        var farMin = min.Concat(new[] { 1e6, 1e6, 1e6 }).ToArray();
        var farMax = max.Concat(new[] { 1e6 + 1, 1e6 + 1, 1e6 + 1 }).ToArray();
        grid.FindPairs(farMin, farMax, count + 1);
        Assert.False(grid.Dense);
        Assert.True(dense.SetEquals(Pairs(grid)));
        Assert.True(dense.SetEquals(BruteForce(min, max, count)));
        Assert.True(WidestWindow(grid, count) > grid.PairCount / 2, "index order spreads a box's pairs over the list");
    }

    [Fact]
    public void Far_apart_coordinates_and_a_filter_are_handled()
    {
        var min = new List<double>();
        var max = new List<double>();
        foreach (var centre in new[] { -1e9, -1e9 + 0.5, 0.0, 0.4, 1e9, 3e11 })
        {
            min.AddRange(new[] { centre - 0.3, -0.3, -0.3 });
            max.AddRange(new[] { centre + 0.3, 0.3, 0.3 });
        }

        var grid = new SpatialHashGrid();
        grid.FindPairs(min.ToArray(), max.ToArray(), 6);
        Assert.Equal(new[] { 0, 2 }, grid.First.ToArray());
        Assert.Equal(new[] { 1, 3 }, grid.Second.ToArray());
        var filter = new ExcludedPairs();
        filter.Add(0, 1);
        grid.FindPairs(min.ToArray(), max.ToArray(), 6, filter);
        Assert.Equal(new[] { 2 }, grid.First.ToArray());
    }

    [Fact]
    public void Bad_box_counts_are_refused()
    {
        var grid = new SpatialHashGrid();
        Assert.Throws<ArgumentException>(() => grid.FindPairs(new double[3], new double[3], 2));
        Assert.Throws<ArgumentException>(() => grid.FindPairs(new double[3], new double[3], -1));
        grid.FindPairs(Array.Empty<double>(), Array.Empty<double>(), 0);
        Assert.Equal(0, grid.PairCount);
    }

    [Fact]
    public void A_search_with_a_limit_stops_there_and_says_so()
    {
        // 40 boxes at one point: 780 pairs. The list never grows past the limit (the contact set's MaxCandidatePairs).
        var min = new double[120];
        var max = Enumerable.Repeat(1.0, 120).ToArray();
        var grid = new SpatialHashGrid();
        Assert.False(grid.TryFindPairs(min, max, 40, null, 779));
        Assert.Equal(779, grid.PairCount);
        Assert.True(grid.TryFindPairs(min, max, 40, null, 780));
        Assert.Equal(780, grid.PairCount);
        Assert.True(grid.TryFindPairs(min, max, 40, null, SpatialHashGrid.MaxPairs));
        Assert.False(grid.TryFindPairs(min, max, 40, null, 100)); // a lower limit holds though the list is longer
        Assert.Equal(100, grid.PairCount);
    }

    /// <summary>Unit boxes on a lattice of spacing 0.9 (so that neighbours, diagonals included, overlap), in a shuffled order.</summary>
    private static (double[] Min, double[] Max) ShuffledLattice(int nx, int ny, int nz, out int count)
    {
        count = nx * ny * nz;
        var order = Enumerable.Range(0, count).ToArray();
        var state = 12345u;
        for (var k = count - 1; k > 0; k--)
        {
            var r = (int)((ObstacleTests.Next(ref state) + 1) * 0.5 * (k + 1)) % (k + 1);
            (order[k], order[r]) = (order[r], order[k]);
        }

        var min = new double[3 * count];
        var max = new double[3 * count];
        for (var site = 0; site < count; site++)
        {
            var i = order[site];
            var centre = new[] { 0.9 * (site % nx), 0.9 * (site / nx % ny), 0.9 * (site / (nx * ny)) };
            for (var c = 0; c < 3; c++)
            {
                min[(3 * i) + c] = centre[c] - 0.5;
                max[(3 * i) + c] = centre[c] + 0.5;
            }
        }

        return (min, max);
    }

    private static HashSet<(int, int)> Pairs(SpatialHashGrid grid) =>
        Enumerable.Range(0, grid.PairCount).Select(p => (grid.First[p], grid.Second[p])).ToHashSet();

    /// <summary>The most places between the first and the last pair of one box in the list.</summary>
    private static int WidestWindow(SpatialHashGrid grid, int count)
    {
        var first = Enumerable.Repeat(int.MaxValue, count).ToArray();
        var last = new int[count];
        for (var p = 0; p < grid.PairCount; p++)
        {
            foreach (var i in new[] { grid.First[p], grid.Second[p] })
            {
                if (i < count)
                {
                    first[i] = Math.Min(first[i], p);
                    last[i] = Math.Max(last[i], p);
                }
            }
        }

        return Enumerable.Range(0, count).Where(i => first[i] <= last[i]).Max(i => last[i] - first[i]);
    }

    private static HashSet<(int, int)> BruteForce(double[] min, double[] max, int count)
    {
        var pairs = new HashSet<(int, int)>();
        for (var i = 0; i < count; i++)
        {
            for (var j = i + 1; j < count; j++)
            {
                if (Enumerable.Range(0, 3).All(c => min[(3 * i) + c] <= max[(3 * j) + c] && min[(3 * j) + c] <= max[(3 * i) + c]))
                {
                    pairs.Add((i, j));
                }
            }
        }

        return pairs;
    }
}
