using System;
using ParticlePhysics.Integrators;
using ParticlePhysics.Parallel;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Engine;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Parallel;

/// <summary>Using several cores changes nothing but the time: same bits, whatever the runner.</summary>
[Collection(AllocationMeasurements.Name)]
public class ParallelRunnerTests
{
    [Theory]
    [MemberData(nameof(DeterminismAndAllocationTests.Integrators), MemberType = typeof(DeterminismAndAllocationTests))]
    public void A_parallel_run_is_bit_identical_to_the_single_threaded_run(string integrator)
    {
        // 40 x 40 cloth: 9 048 springs, above the parallel threshold.
        var serial = Cloth();
        StateMetrics.Run(serial, IntegratorCatalog.Create(integrator), 1e-4, 20);
        using var runner = new WorkerThreadRunner(2);
        var parallel = Cloth();
        parallel.Runner = runner;
        StateMetrics.Run(parallel, IntegratorCatalog.Create(integrator), 1e-4, 20);
        Assert.Equal(StateMetrics.BitHash(serial.State), StateMetrics.BitHash(parallel.State));
    }

    [Fact]
    public void A_host_runner_with_its_own_scheduling_gives_the_same_bits()
    {
        var serial = Cloth();
        StateMetrics.Run(serial, new RungeKutta4(), 1e-4, 10);
        var hosted = Cloth();
        hosted.Runner = new ReverseOrderRunner();
        StateMetrics.Run(hosted, new RungeKutta4(), 1e-4, 10);
        using var three = new WorkerThreadRunner(3);
        var threeThreads = Cloth();
        threeThreads.Runner = three;
        StateMetrics.Run(threeThreads, new RungeKutta4(), 1e-4, 10);
        Assert.Equal(StateMetrics.BitHash(serial.State), StateMetrics.BitHash(hosted.State));
        Assert.Equal(StateMetrics.BitHash(serial.State), StateMetrics.BitHash(threeThreads.State));
    }

    [Fact]
    public void Runs_every_chunk_once_and_rethrows_a_chunk_failure()
    {
        using var runner = new WorkerThreadRunner(2);
        var counter = new CountingWork();
        runner.Run(counter, 1000);
        Assert.All(counter.Counts, count => Assert.Equal(1, count));
        var ex = Assert.Throws<InvalidOperationException>(() => runner.Run(new FailingWork(), 64));
        Assert.Equal("chunk 13", ex.Message);
        runner.Run(counter, 1000); // still usable after a failure
        Assert.All(counter.Counts, count => Assert.Equal(2, count));
    }

    [Fact]
    public void Stepping_with_a_runner_allocates_nothing_on_the_calling_thread()
    {
        using var runner = new WorkerThreadRunner(2);
        var system = Cloth();
        system.Runner = runner;
        var rk4 = new RungeKutta4();
        StateMetrics.Run(system, rk4, 1e-4, 3);
        var before = GC.GetAllocatedBytesForCurrentThread();
        StateMetrics.Run(system, rk4, 1e-4, 50);
        Assert.Equal(0, GC.GetAllocatedBytesForCurrentThread() - before);
    }

    [Fact]
    public void Invalid_parallelism_is_refused_and_a_disposed_runner_says_so()
    {
        Assert.Throws<ArgumentOutOfRangeException>("parallelism", () => new WorkerThreadRunner(-1));
        var runner = new WorkerThreadRunner(2);
        runner.Dispose();
        Assert.Throws<ObjectDisposedException>(() => runner.Run(new CountingWork(), 4));
    }

    private static ParticleWorld Cloth() => new ClothScenario { Resolution = 1.0 / 39 }.Build();

    /// <summary>A host's scheduler, here one that runs the chunks on the thread pool in reverse order.</summary>
    private sealed class ReverseOrderRunner : IParallelRunner
    {
        public int MaxParallelism => 4;

        public void Run(IParallelWork work, int chunkCount) =>
            System.Threading.Tasks.Parallel.For(0, chunkCount, i => work.Execute(chunkCount - 1 - i, chunkCount));
    }

    private sealed class CountingWork : IParallelWork
    {
        public int[] Counts { get; } = new int[1000];

        public void Execute(int chunk, int chunkCount) => System.Threading.Interlocked.Increment(ref Counts[chunk]);
    }

    private sealed class FailingWork : IParallelWork
    {
        public void Execute(int chunk, int chunkCount)
        {
            if (chunk == 13)
            {
                throw new InvalidOperationException("chunk 13");
            }
        }
    }
}
