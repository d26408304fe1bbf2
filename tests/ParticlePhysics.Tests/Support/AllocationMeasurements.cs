namespace ParticlePhysics.Tests.Support;

/// <summary>
/// The test classes that count the bytes a thread allocates (GC.GetAllocatedBytesForCurrentThread) run in this
/// collection, alone, after the parallel ones: a garbage collection that another test's allocations trigger in the
/// middle of a measurement can move the calling thread's count (seen once in CI: 1576 bytes over 50 steps that allocate
/// nothing, never reproduced in 300 runs of the same steps in a process of their own). Running alone did not end such
/// counts (the runtime's own miscount; see <see cref="ThreadAllocations"/>), so they measure through ThreadAllocations,
/// which measures again a count that is not zero.
/// </summary>
[CollectionDefinition(Name, DisableParallelization = true)]
public sealed class AllocationMeasurements
{
    public const string Name = "Allocation measurements";
}
