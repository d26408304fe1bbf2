using System;
using System.Diagnostics;
using System.Threading;
using ParticlePhysics.Parallel;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Parallel;

/// <summary>A run allocates nothing on any thread: the caller's, and each worker's, whether it spun or slept.</summary>
[Collection(AllocationMeasurements.Name)]
public class WorkerThreadRunnerAllocationTests
{
    [Theory]
    [InlineData(2, "adaptive")]
    [InlineData(3, "never-spin")]
    [InlineData(3, "always-spin-1us")]
    public void No_thread_allocates_per_run(int parallelism, string mode)
    {
        var random = new Random(7);
        var pauses = new int[20_000];
        for (var i = 0; i < pauses.Length; i++)
        {
            pauses[i] = random.Next(1000);
        }

        using var runner = WorkerThreadRunnerTests.Create(parallelism, mode);
        var probe = new AllocationProbe(parallelism);
        var work = new TinyWork();
        for (var i = 0; i < 1000; i++)
        {
            runner.Run(work, 1 + (i % (2 * parallelism)));
        }

        // Every thread takes one chunk of a run that needs all of them at once, and notes its allocated bytes.
        probe.Reset(first: true);
        runner.Run(probe, parallelism);
        var callerBefore = GC.GetAllocatedBytesForCurrentThread();
        for (var i = 0; i < pauses.Length; i++)
        {
            runner.Run(work, 1 + (i % (2 * parallelism)));
            if (pauses[i] < 5)
            {
                Thread.Sleep(1); // long enough for the workers to go to sleep: the sleeping path runs too
            }
            else if (pauses[i] < 100)
            {
                Thread.SpinWait(pauses[i] * 20);
            }
        }

        var callerAllocated = GC.GetAllocatedBytesForCurrentThread() - callerBefore;
        probe.Reset(first: false);
        runner.Run(probe, parallelism);
        Assert.Equal(0, callerAllocated);
        for (var t = 0; t < parallelism; t++)
        {
            Assert.True(probe.Thread[t] == probe.ThreadAfter[t], $"chunk {t} ran on two different threads");
            Assert.Equal(0, probe.After[t] - probe.Before[t]);
        }
    }

    private sealed class TinyWork : IParallelWork
    {
        private long _sum;

        public void Execute(int chunk, int chunkCount) => Interlocked.Add(ref _sum, chunk);
    }

    /// <summary>
    /// A run whose chunks wait for each other (so each thread takes exactly one) and note the thread's allocated
    /// bytes; chunk t is matched to the same thread in both runs through the thread's id.
    /// </summary>
    private sealed class AllocationProbe : IParallelWork
    {
        private readonly int _parties;
        private int _arrived;
        private bool _first;

        public AllocationProbe(int parties)
        {
            _parties = parties;
            Before = new long[parties];
            After = new long[parties];
            Thread = new int[parties];
            ThreadAfter = new int[parties];
        }

        public long[] Before { get; }

        public long[] After { get; }

        public int[] Thread { get; }

        public int[] ThreadAfter { get; }

        public void Reset(bool first)
        {
            _arrived = 0;
            _first = first;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var bytes = GC.GetAllocatedBytesForCurrentThread();
            var id = Environment.CurrentManagedThreadId;
            Interlocked.Increment(ref _arrived);
            var spinner = default(SpinWait);
            var start = Stopwatch.GetTimestamp();
            while (Volatile.Read(ref _arrived) < _parties)
            {
                if (Stopwatch.GetElapsedTime(start) > TimeSpan.FromSeconds(10))
                {
                    throw new TimeoutException($"chunk {chunk}: not every thread came");
                }

                spinner.SpinOnce(sleep1Threshold: -1);
            }

            if (_first)
            {
                Thread[chunk] = id;
                Before[chunk] = bytes;
                return;
            }

            // The second run may give this thread another chunk number: file it under the first run's.
            var slot = Array.IndexOf(Thread, id);
            ThreadAfter[slot < 0 ? chunk : slot] = id;
            After[slot < 0 ? chunk : slot] = bytes;
        }
    }
}
