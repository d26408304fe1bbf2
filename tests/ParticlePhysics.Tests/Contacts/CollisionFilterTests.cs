using System;
using ParticlePhysics.Contacts;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Tests.Contacts;

/// <summary>Layers and masks between groups of particles and obstacles (<see cref="CollisionFilter"/>).</summary>
public class CollisionFilterTests
{
    [Fact]
    public void The_default_is_layer_one_colliding_with_every_layer()
    {
        Assert.Equal(CollisionFilter.Default, default);
        Assert.Equal(1u, CollisionFilter.Default.Layers);
        Assert.Equal(uint.MaxValue, CollisionFilter.Default.Mask);
        var cloth = new CollisionFilter(layers: 2, mask: ~4u);
        var hand = new CollisionFilter(layers: 4, mask: uint.MaxValue);
        Assert.Equal((2u, ~4u), (cloth.Layers, cloth.Mask));
        Assert.False(cloth.Accepts(hand));
        Assert.False(hand.Accepts(cloth));
        Assert.True(cloth.Accepts(CollisionFilter.Default));
        Assert.True(new CollisionFilter(8, 8).Accepts(new CollisionFilter(8, 8)));
        Assert.False(new CollisionFilter(8, 8).Accepts(CollisionFilter.Default)); // its mask leaves out layer 1
    }

    [Theory]
    [InlineData("rk4")]
    [InlineData("xpbd")]
    public void A_group_passes_the_obstacles_its_mask_leaves_out_and_lands_on_the_rest(string integrator)
    {
        // Two particles above a box over the ground; particle 1 is in layer 2, whose mask leaves out the box's layer 3.
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(0, 2, 0), 1.0);
        world.AddParticle(new Vector3d(0.5, 2, 0), 1.0);
        world.SetRadius(0, 0.05);
        world.SetRadius(1, 0.05);
        world.AddForce(new Gravity());
        var contacts = new ContactSet();
        contacts.Add(PlaneObstacle.Ground());
        contacts.Add(new BoxObstacle(new Vector3d(0.25, 0.5, 0), new Vector3d(1, 0.1, 1)) { Filter = new CollisionFilter(4, uint.MaxValue) });
        contacts.SetParticleFilter(1, 1, new CollisionFilter(2, ~4u));
        world.AddConstraints(contacts);
        var method = IntegratorCatalog.Create(integrator);
        for (var step = 0; step < 120; step++)
        {
            world.Step(method, 1.0 / 60.0);
        }

        Assert.Equal(0.65, world.GetPosition(0).Y, 6); // on the box
        Assert.Equal(0.05, world.GetPosition(1).Y, 6); // through it, on the ground
        Assert.Equal(new CollisionFilter(2, ~4u), contacts.GetParticleFilter(1));
        Assert.Equal(CollisionFilter.Default, contacts.GetParticleFilter(0));
        Assert.Equal(CollisionFilter.Default, contacts.GetParticleFilter(1000));
    }

    [Fact]
    public void Two_groups_that_leave_each_other_out_pass_through_each_other_and_each_still_collides_within_itself()
    {
        // Two pairs of particles flying at each other head-on: 0 against 1 (one group), 2 against 3 (the other group
        // each), on parallel lines; a third line crosses group A against group B.
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(-1, 0, 0), new Vector3d(2, 0, 0), 1.0);
        world.AddParticle(new Vector3d(1, 0, 0), new Vector3d(-2, 0, 0), 1.0);
        world.AddParticle(new Vector3d(-1, 1, 0), new Vector3d(2, 0, 0), 1.0);
        world.AddParticle(new Vector3d(1, 1, 0), new Vector3d(-2, 0, 0), 1.0);
        for (var i = 0; i < 4; i++)
        {
            world.SetRadius(i, 0.1);
        }

        var contacts = new ContactSet { ParticleCollisions = true, ParticleRestitution = 1 };
        contacts.SetParticleFilter(0, 2, new CollisionFilter(2, 2)); // group A: 0, 1
        contacts.SetParticleFilter(2, 1, new CollisionFilter(2, 2)); // 2 is in group A too
        contacts.SetParticleFilter(3, 1, new CollisionFilter(4, 4)); // 3 in group B
        world.AddConstraints(contacts);
        var rk4 = new RungeKutta4();
        for (var step = 0; step < 60; step++)
        {
            world.Step(rk4, 1.0 / 60.0);
        }

        Assert.True(world.GetPosition(0).X < 0 && world.GetPosition(1).X > 0, "within a group they bounce");
        Assert.True(world.GetPosition(2).X > 0 && world.GetPosition(3).X < 0, "across groups they pass");
    }

    [Fact]
    public void Bad_ranges_are_refused_naming_the_value()
    {
        var contacts = new ContactSet();
        Assert.Equal("first", Assert.Throws<ArgumentOutOfRangeException>(() => contacts.SetParticleFilter(-1, 2, default)).ParamName);
        Assert.Equal("count", Assert.Throws<ArgumentOutOfRangeException>(() => contacts.SetParticleFilter(0, -2, default)).ParamName);
        Assert.Equal("count", Assert.Throws<ArgumentOutOfRangeException>(() => contacts.SetParticleFilter(1, ParticleWorld.MaxParticles, default)).ParamName);
        Assert.Equal("particle", Assert.Throws<ArgumentOutOfRangeException>(() => contacts.GetParticleFilter(-1)).ParamName);
    }
}
