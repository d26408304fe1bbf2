using System;

namespace ParticlePhysics.Tests.Support;

/// <summary>The measurement that the allocation tests rely on: it forgives no allocation that happens every time.</summary>
[Collection(AllocationMeasurements.Name)]
public class ThreadAllocationsTests
{
    [Fact]
    public void Work_that_allocates_every_time_is_counted_every_time()
    {
        var runs = 0;
        var kept = Array.Empty<byte>();
        var bytes = ThreadAllocations.Measure(() =>
        {
            kept = new byte[1000];
            runs++;
        });

        Assert.Equal(ThreadAllocations.Attempts, runs);
        Assert.InRange(bytes, 1000, 1100);
        Assert.Equal(1000, kept.Length);
    }

    [Fact]
    public void Work_that_allocates_nothing_is_measured_once()
    {
        var runs = 0;
        var sum = 0.0;
        var values = new double[64];
        Assert.Equal(0, ThreadAllocations.Measure(() =>
        {
            foreach (var value in values)
            {
                sum += value;
            }

            runs++;
        }));
        Assert.Equal(1, runs);
        Assert.Equal(0.0, sum);
    }

    [Fact]
    public void Work_that_allocates_only_its_first_time_counts_nothing()
    {
        // What the measurement forgives: a count that does not come back (here a real one, for the test's sake).
        var runs = 0;
        object? kept = null;
        Assert.Equal(0, ThreadAllocations.Measure(() =>
        {
            kept ??= new byte[1000];
            runs++;
        }));
        Assert.Equal(2, runs);
        Assert.NotNull(kept);
    }
}
