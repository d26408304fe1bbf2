using System;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Engine;

/// <summary>A profiled step allocates nothing, whatever the integrator and whatever the world holds.</summary>
[Collection(AllocationMeasurements.Name)]
public class StepProfileAllocationTests
{
    [Theory]
    [MemberData(nameof(DeterminismAndAllocationTests.Integrators), MemberType = typeof(DeterminismAndAllocationTests))]
    public void A_profiled_step_allocates_nothing(string integrator)
    {
        foreach (var build in new Func<ParticleWorld>[]
        {
            () => new ClothScenario { Resolution = 1.0 / 11 }.Build(),
            new PendulumScenario().Build,
            new BouncingBallScenario().Build,
        })
        {
            var world = build();
            world.Profiling = true;
            var stepper = IntegratorCatalog.Create(integrator);
            StateMetrics.Run(world, stepper, 0.002, 5);
            var sum = default(StepProfile);
            var allocated = ThreadAllocations.Measure(() =>
            {
                for (var step = 0; step < 50; step++)
                {
                    world.Step(stepper, 0.002);
                    sum += world.LastStepProfile;
                }
            });
            Assert.Equal(0, allocated);
            Assert.True(sum.ForceEvaluations >= 50);
        }
    }
}
