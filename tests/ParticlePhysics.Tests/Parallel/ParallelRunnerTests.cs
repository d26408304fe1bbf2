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
    public void Xpbd_runs_a_substep_in_three_hand_offs_with_the_same_bits_on_any_runner()
    {
        // The 64 x 64 cloth at 60 Hz: 4096 particles, 23 938 springs in 12 strips of 5 1/3 rows, and anchored springs
        // on a third of the particles so that the batches hold both kinds. Per substep: the even strips with their
        // seams, the odd strips, the velocities (the prediction stays on the calling thread below 16 384 particles).
        // It was 15: the prediction, each of the 13 colours, the velocities. One core; runners of parallelism 1, 2 and 3; a host scheduler that runs the chunks
        // concurrently in reverse order, and one that runs them one at a time in reverse order.
        var serial = XpbdCloth(out _);
        StateMetrics.Run(serial, new Xpbd(), 1.0 / 60, 20);
        var expected = StateMetrics.BitHash(serial.State);
        using var one = new WorkerThreadRunner(1);
        using var two = new WorkerThreadRunner(2);
        using var three = new WorkerThreadRunner(3);
        foreach (var runner in new IParallelRunner[] { one, two, three, new ReverseOrderRunner(), new SequentialReverseRunner() })
        {
            var counting = new CountingRunner(runner);
            var parallel = XpbdCloth(out var phases);
            parallel.Runner = counting;
            StateMetrics.Run(parallel, new Xpbd(), 1.0 / 60, 20);
            Assert.Equal(expected, StateMetrics.BitHash(parallel.State));
            if (runner.MaxParallelism == 1)
            {
                Assert.Equal(0, counting.Runs); // nothing to share
                continue;
            }

            Assert.Equal(2, phases);
            Assert.Equal(20 * 10 * (phases + 1), counting.Runs);
            Assert.True(counting.SmallestChunkCount > 1, $"a pass ran in {counting.SmallestChunkCount} chunk");
        }
    }

    [Fact]
    public void Xpbd_splits_the_prediction_of_a_large_cloth_with_the_same_bits()
    {
        // The 128 x 128 cloth, 16 384 particles: from there the prediction runs in chunks of at least 8192 particles, so
        // a substep hands off one more pass than the 64 x 64 cloth's three (the prediction, the projection's phases,
        // the velocities).
        var serial = new ClothScenario { Resolution = 1.0 / 127 }.Build();
        StateMetrics.Run(serial, new Xpbd(), 1.0 / 60, 2);
        using var two = new WorkerThreadRunner(2);
        foreach (var runner in new IParallelRunner[] { two, new SequentialReverseRunner() })
        {
            var cloth = new ClothScenario { Resolution = 1.0 / 127 }.CreateBuilder().Build();
            var counting = new CountingRunner(runner);
            cloth.System.Runner = counting;
            StateMetrics.Run(cloth.System, new Xpbd(), 1.0 / 60, 2);
            Assert.Equal(StateMetrics.BitHash(serial.State), StateMetrics.BitHash(cloth.System.State));
            var phases = cloth.Projection.PhaseStarts.Length - 1;
            Assert.Equal(2 * 10 * (phases + 2), counting.Runs);
        }
    }

    [Fact]
    public void Xpbd_with_a_runner_allocates_nothing_on_the_calling_thread()
    {
        using var runner = new WorkerThreadRunner(2);
        var world = XpbdCloth(out _);
        world.Runner = runner;
        var xpbd = new Xpbd();
        StateMetrics.Run(world, xpbd, 1.0 / 60, 3);
        Assert.Equal(0, ThreadAllocations.Measure(() => StateMetrics.Run(world, xpbd, 1.0 / 60, 30)));
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
        Assert.Equal(0, ThreadAllocations.Measure(() => StateMetrics.Run(system, rk4, 1e-4, 50)));
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

    /// <summary>The 64 x 64 cloth with an anchored spring on every third particle, and its projection's phase count.</summary>
    private static ParticleWorld XpbdCloth(out int phases)
    {
        var cloth = new ClothScenario { Resolution = 1.0 / 63 }.CreateBuilder().Build();
        for (var i = 2; i < cloth.System.Count; i += 3)
        {
            var p = cloth.System.GetPosition(i);
            cloth.Springs.AddAnchored(i, new Vector3d(p.X, 0.1, p.Z), 5, 0.1, 0.01);
        }

        cloth.System.Step(new Xpbd(), 1.0 / 60);
        phases = cloth.Projection.PhaseStarts.Length - 1;
        cloth.System.SetState(new ClothScenario { Resolution = 1.0 / 63 }.Build().State);
        cloth.System.Time = 0;
        return cloth.System;
    }

    /// <summary>A host's scheduler, here one that runs the chunks on the thread pool in reverse order.</summary>
    private sealed class ReverseOrderRunner : IParallelRunner
    {
        public int MaxParallelism => 4;

        public void Run(IParallelWork work, int chunkCount) =>
            System.Threading.Tasks.Parallel.For(0, chunkCount, i => work.Execute(chunkCount - 1 - i, chunkCount));
    }

    /// <summary>A host's scheduler that runs the chunks one at a time, last first, on the calling thread.</summary>
    private sealed class SequentialReverseRunner : IParallelRunner
    {
        public int MaxParallelism => 2;

        public void Run(IParallelWork work, int chunkCount)
        {
            for (var chunk = chunkCount - 1; chunk >= 0; chunk--)
            {
                work.Execute(chunk, chunkCount);
            }
        }
    }

    /// <summary>A runner that counts its calls and the fewest chunks it was asked for, and hands the work on.</summary>
    private sealed class CountingRunner : IParallelRunner
    {
        private readonly IParallelRunner _inner;

        public CountingRunner(IParallelRunner inner)
        {
            _inner = inner;
        }

        public int Runs { get; private set; }

        public int SmallestChunkCount { get; private set; } = int.MaxValue;

        public int MaxParallelism => _inner.MaxParallelism;

        public void Run(IParallelWork work, int chunkCount)
        {
            Runs++;
            SmallestChunkCount = Math.Min(SmallestChunkCount, chunkCount);
            _inner.Run(work, chunkCount);
        }
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
