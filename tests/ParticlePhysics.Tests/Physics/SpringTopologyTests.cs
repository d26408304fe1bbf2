using System;
using ParticlePhysics.Constraints;
using ParticlePhysics.Forces;

namespace ParticlePhysics.Tests.Physics;

/// <summary>Springs, rods and cables tell what they join (a renderer draws them from it), and refuse an index they do not have.</summary>
public class SpringTopologyTests
{
    [Fact]
    public void A_spring_network_gives_back_the_ends_and_anchors_it_was_built_with()
    {
        var world = new ParticleWorld();
        world.AddParticle(Vector3d.Zero, 1);
        world.AddParticle(new Vector3d(1, 0, 0), 1);
        world.AddParticle(new Vector3d(2, 0, 0), 1);
        var springs = new SpringNetwork(world);
        springs.Add(2, 0, 10, 1);
        springs.AddAnchored(1, new Vector3d(0.5, 3, -2), 10, 1);
        springs.AddAnchored(2, new Vector3d(7, 8, 9), 10, 1);

        Assert.Equal((2, 0), springs.GetEnds(0));
        Assert.Equal((1, new Vector3d(0.5, 3, -2)), springs.GetAnchoredSpring(0));
        Assert.Equal((2, new Vector3d(7, 8, 9)), springs.GetAnchoredSpring(1));
        Assert.Throws<ArgumentOutOfRangeException>(() => springs.GetAnchoredSpring(2));
        Assert.Throws<ArgumentOutOfRangeException>(() => springs.GetAnchoredSpring(-1));
    }

    [Fact]
    public void Zero_length_springs_give_back_their_ends_and_anchors_also_after_the_anchor_moves()
    {
        var world = new ParticleWorld();
        world.AddParticle(Vector3d.Zero, 1);
        world.AddParticle(new Vector3d(1, 0, 0), 1);
        var springs = new ZeroLengthSprings(world);
        springs.Add(1, 0, 5);
        springs.AddAnchored(0, new Vector3d(1, 2, 3), 5);

        Assert.Equal((1, 0), springs.GetEnds(0));
        Assert.Equal((0, new Vector3d(1, 2, 3)), springs.GetAnchoredSpring(0));
        springs.SetAnchor(0, new Vector3d(-4, 0, 4));
        Assert.Equal((0, new Vector3d(-4, 0, 4)), springs.GetAnchoredSpring(0));
        Assert.Throws<ArgumentOutOfRangeException>(() => springs.GetEnds(1));
        Assert.Throws<ArgumentOutOfRangeException>(() => springs.GetAnchoredSpring(1));
    }

    [Fact]
    public void A_rod_network_gives_back_its_anchors_and_refuses_one_for_a_link_between_particles()
    {
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(1, 0, 0), 1);
        world.AddParticle(new Vector3d(2, 0, 0), 1);
        var rods = new RodNetwork(world);
        rods.AddRod(0, 1, 1);
        rods.AddAnchoredCable(1, new Vector3d(2, 3, 4), 5);

        Assert.Equal((1, -1), rods.GetEnds(1));
        Assert.True(rods.IsCable(1));
        Assert.Equal(new Vector3d(2, 3, 4), rods.GetAnchor(1));
        Assert.Throws<ArgumentException>(() => rods.GetAnchor(0));
        Assert.Throws<ArgumentOutOfRangeException>(() => rods.GetAnchor(2));
    }
}
