using System;
using System.Collections.Generic;
using System.Linq;
using ParticlePhysics.Contacts;

namespace ParticlePhysics.Tests.Contacts;

/// <summary>The spatial hash finds exactly the overlapping pairs that brute force finds.</summary>
public class BroadPhaseTests
{
    [Theory]
    [InlineData(1, 0.1, 0)]
    [InlineData(500, 0.05, 0)]
    [InlineData(2000, 0.02, 5)]
    [InlineData(3000, 0.2, 40)]
    public void The_grid_finds_exactly_the_pairs_brute_force_finds(int count, double size, int large)
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
