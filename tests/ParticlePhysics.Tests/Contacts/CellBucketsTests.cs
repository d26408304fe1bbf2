using System.Collections.Generic;
using ParticlePhysics.Contacts;

namespace ParticlePhysics.Tests.Contacts;

/// <summary>The broad phase's table of cells: a dense box numbered shortest axis fastest, or a hash.</summary>
public class CellBucketsTests
{
    [Fact]
    public void A_small_box_of_cells_is_numbered_one_bucket_per_cell_shortest_axis_fastest()
    {
        // 5 x 2 x 7 cells from (-3, 10, 4): y (2 cells) fastest, then x (5), then z (7).
        var buckets = default(CellBuckets);
        buckets.Fit(-3, 10, 4, 1, 11, 10, 20);
        Assert.True(buckets.Dense);
        Assert.Equal(70, buckets.Count);
        var seen = new HashSet<int>();
        for (long x = -3; x <= 1; x++)
        {
            for (long y = 10; y <= 11; y++)
            {
                for (long z = 4; z <= 10; z++)
                {
                    var bucket = buckets.Of(x, y, z, 0);
                    Assert.Equal((y - 10) + (2 * (x + 3)) + (10 * (z - 4)), bucket);
                    Assert.True(seen.Add(bucket));
                }
            }
        }

        Assert.Equal(-1, buckets.Of(-4, 10, 4, 0));
        Assert.Equal(-1, buckets.Of(1, 12, 4, 0));
        Assert.Equal(-1, buckets.Of(0, 10, 11, 0));
    }

    [Fact]
    public void Ties_keep_the_x_y_z_order_and_a_large_box_is_hashed()
    {
        var buckets = default(CellBuckets);
        buckets.Fit(0, 0, 0, 2, 2, 2, 10);
        Assert.True(buckets.Dense);
        Assert.Equal(1, buckets.Of(1, 0, 0, 0));
        Assert.Equal(3, buckets.Of(0, 1, 0, 0));
        Assert.Equal(9, buckets.Of(0, 0, 1, 0));

        // 41 cells per box (over 4 per box): a hash of 2^k >= 2 N buckets, every cell in one of them.
        buckets.Fit(0, 0, 0, 40, 0, 0, 10);
        Assert.False(buckets.Dense);
        Assert.Equal(32, buckets.Count);
        for (long x = -100; x < 100; x++)
        {
            Assert.InRange(buckets.Of(x, 0, 0, (x + 7) * 1000003), 0, 31);
        }

        // Coordinates far apart on every axis: no overflow of n_x n_y n_z.
        buckets.Fit(-1048574, -1048574, -1048574, 1048574, 1048574, 1048574, 1000);
        Assert.False(buckets.Dense);
    }
}
