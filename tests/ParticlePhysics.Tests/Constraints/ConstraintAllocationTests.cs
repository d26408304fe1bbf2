using System;
using ParticlePhysics.Constraints;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Engine;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Constraints;

/// <summary>Rods, cables, projections and moving anchors step without allocating, and deterministically.</summary>
[Collection(AllocationMeasurements.Name)]
public class ConstraintAllocationTests
{
    [Theory]
    [MemberData(nameof(DeterminismAndAllocationTests.Integrators), MemberType = typeof(DeterminismAndAllocationTests))]
    public void Chains_nets_and_cables_step_without_allocating_and_repeat_bit_for_bit(string integrator)
    {
        foreach (var build in new Func<ParticleWorld>[] { new HangingChainScenario().Build, Net, CableAndKinematicAnchor })
        {
            var world = build();
            var stepper = IntegratorCatalog.Create(integrator);
            StateMetrics.Run(world, stepper, 0.001, 5);
            var steps = 5;
            var allocated = ThreadAllocations.Measure(() =>
            {
                StateMetrics.Run(world, stepper, 0.001, 100);
                steps += 100; // (100 more when a count was not zero and the steps were measured again)
            });
            Assert.Equal(0, allocated);

            var again = build();
            StateMetrics.Run(again, IntegratorCatalog.Create(integrator), 0.001, steps);
            Assert.Equal(StateMetrics.BitHash(world.State), StateMetrics.BitHash(again.State));
        }
    }

    /// <summary>A 12 x 12 net of rods from one corner: wide enough a band for conjugate gradients.</summary>
    private static ParticleWorld Net()
    {
        const int side = 12;
        var world = new ParticleWorld();
        for (var i = 0; i < side * side; i++)
        {
            world.AddParticle(new Vector3d(i % side * 0.05, 0, i / side * 0.05), 0.01);
        }

        world.Pin(0);
        world.AddForce(new Forces.Gravity());
        var rods = new RodNetwork(world);
        for (var i = 0; i < side * side; i++)
        {
            if (i % side + 1 < side)
            {
                rods.AddRod(i, i + 1, 0.05);
            }

            if (i + side < side * side)
            {
                rods.AddRod(i, i + side, 0.05);
            }
        }

        Assert.False(rods.SolvesDirectly);
        world.AddConstraints(rods);
        return world;
    }

    /// <summary>A mass on a cable from a pinned particle that moves, with a damped spring beside it.</summary>
    private static ParticleWorld CableAndKinematicAnchor()
    {
        var world = new ParticleWorld();
        world.AddParticle(Vector3d.Zero, 1);
        world.AddParticle(new Vector3d(0.3, -0.5, 0), 0.5);
        world.Pin(0, new Vector3d(0.2, 0, 0));
        world.AddForce(new Forces.Gravity());
        var springs = new Forces.SpringNetwork(world);
        springs.Add(0, 1, 30, 0.4, 0.3);
        world.AddForce(springs);
        world.AddConstraints(new SpringProjection(springs));
        var cables = new RodNetwork(world);
        cables.AddCable(0, 1, 0.7);
        world.AddConstraints(cables);
        return world;
    }
}
