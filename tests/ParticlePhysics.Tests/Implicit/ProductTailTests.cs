using System;
using System.Linq;
using ParticlePhysics.Cloth;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Internal;
using ParticlePhysics.Parallel;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Implicit;

/// <summary>
/// The uniform tail of the world's Jacobian product (IJacobianProductTail): a drag on every particle after the
/// springs is left to the conjugate gradients' passes, which add c w to the product they read, the operation the drag's
/// own pass did. Which generators make a tail, and that the steps keep their bits.
/// </summary>
public class ProductTailTests
{
    private const double Frame = 1.0 / 60;

    [Fact]
    public void A_cloth_whose_drag_names_every_particle_steps_to_the_same_bits_without_a_tail()
    {
        // Build() drags every particle (a uniform tail); AddTo() drags a list of all of them, whose product is a loop
        // of its own (no tail), then the same gravity after it: the same generators in the same order, the same
        // operations on every value, so the same bits whether the passes or the drag add c w.
        var builder = new ClothBuilder { Rows = 24, Columns = 24 };
        var (withTail, withoutTail) = Pair(builder);
        Assert.Equal(withTail.Forces.Count, withoutTail.Forces.Count);

        var a = new ImplicitEuler { Tolerance = 1e-6 };
        var b = new ImplicitEuler { Tolerance = 1e-6 };
        for (var step = 0; step < 30; step++)
        {
            withTail.Step(a, Frame);
            withoutTail.Step(b, Frame);
            Assert.Equal(a.LastIterations, b.LastIterations);
        }

        Assert.True(Tail(withTail, out var coefficient));
        Assert.Equal(-builder.Drag * Frame, coefficient);
        Assert.False(Tail(withoutTail, out _));
        Assert.Equal(StateMetrics.BitHash(withoutTail.State), StateMetrics.BitHash(withTail.State));
    }

    [Fact]
    public void The_same_bits_with_a_tail_on_a_runner_and_under_block_jacobi()
    {
        var builder = new ClothBuilder { Rows = 24, Columns = 24 };
        using var runner = new WorkerThreadRunner(2);
        foreach (var preconditioner in new[] { ImplicitPreconditioner.Multigrid, ImplicitPreconditioner.BlockJacobi })
        {
            var (withTail, withoutTail) = Pair(builder);
            withTail.Runner = runner;
            var a = new ImplicitEuler { Preconditioner = preconditioner };
            var b = new ImplicitEuler { Preconditioner = preconditioner };
            StateMetrics.Run(withTail, a, Frame, 20);
            StateMetrics.Run(withoutTail, b, Frame, 20);
            Assert.Equal(StateMetrics.BitHash(withoutTail.State), StateMetrics.BitHash(withTail.State));
        }
    }

    [Fact]
    public void Only_a_uniform_term_with_nothing_after_it_but_products_of_nothing_is_a_tail()
    {
        Assert.True(Tail(World(w => new IForceGenerator[] { Springs(w), new LinearDrag(0.5), Gravity.Down(9.81) }), out var c));
        Assert.Equal(-0.5 * Frame, c);
        Assert.True(Tail(World(w => new IForceGenerator[] { Springs(w), new LinearDrag(0.5) }), out _));
        Assert.False(Tail(World(w => new IForceGenerator[] { new LinearDrag(0.5), Springs(w) }), out _)); // springs after it
        Assert.False(Tail(World(w => new IForceGenerator[] { Springs(w), Gravity.Down(9.81) }), out _)); // nothing uniform
        Assert.False(Tail(World(w => new IForceGenerator[] { Springs(w), new LinearDrag(0.5, w, new[] { 0, 1 }) }), out _));
        Assert.True(Tail(World(w => new IForceGenerator[] { Springs(w), new LinearDrag(0.5), new LinearDrag(0.25) }), out c));
        Assert.Equal(-0.25 * Frame, c); // the last drag; the one before it stays in the product before the tail
    }

    [Fact]
    public void The_product_before_the_tail_needs_a_linearisation_and_a_tail()
    {
        var world = World(w => new IForceGenerator[] { Springs(w), new LinearDrag(0.5) });
        var split = (IJacobianProductTail)world;
        var w = new double[3 * world.Count];
        var result = new double[3 * world.Count];
        Assert.False(split.TryGetUniformTail(out _)); // not linearised yet
        Assert.Throws<InvalidOperationException>(() => split.AddJacobianProductBeforeTail(w, result));

        Linearize(world);
        Assert.True(split.TryGetUniformTail(out _));
        world.AddForce(new Gravity(new Vector3d(0, -1, 0)));
        Assert.False(split.TryGetUniformTail(out _)); // a generator added since
        Assert.Throws<InvalidOperationException>(() => split.AddJacobianProductBeforeTail(w, result));
    }

    [Fact]
    public void The_product_before_the_tail_plus_c_w_is_the_whole_product()
    {
        var world = World(w => new IForceGenerator[] { Springs(w), new LinearDrag(0.5), Gravity.Down(9.81) });
        Linearize(world);
        var random = new Random(7);
        var x = Enumerable.Range(0, 3 * world.Count).Select(_ => random.NextDouble() - 0.5).ToArray();
        var whole = new double[x.Length];
        var before = new double[x.Length];
        ((ILinearizableSystem)world).AddJacobianProduct(x, whole);
        var split = (IJacobianProductTail)world;
        Assert.True(split.TryGetUniformTail(out var c));
        split.AddJacobianProductBeforeTail(x, before);
        for (var k = 0; k < x.Length; k++)
        {
            before[k] += c * x[k];
        }

        Assert.Equal(whole, before);
    }

    /// <summary>
    /// The builder's cloth twice: as Build() makes it, with a drag on every particle (a uniform tail), and by AddTo(),
    /// whose drag lists every particle (no tail), followed by the same gravity.
    /// </summary>
    private static (ParticleWorld WithTail, ParticleWorld WithoutTail) Pair(ClothBuilder builder)
    {
        var withoutTail = new ParticleWorld(0);
        builder.AddTo(withoutTail);
        withoutTail.AddForce(Gravity.Down(builder.Gravity));
        return (builder.Build().System, withoutTail);
    }

    private static bool Tail(ParticleWorld world, out double coefficient)
    {
        Linearize(world);
        return ((IJacobianProductTail)world).TryGetUniformTail(out coefficient);
    }

    private static void Linearize(ParticleWorld world)
    {
        var linearizable = (ILinearizableSystem)world;
        var n = 3 * world.Count;
        linearizable.Linearize(0.0, world.State.Slice(0, n), world.State.Slice(n, n), Frame * Frame, Frame, UserForceTreatment.Explicit, new double[n]);
    }

    private static ParticleWorld World(Func<ParticleWorld, IForceGenerator[]> generators)
    {
        var world = new ParticleWorld();
        world.AddParticle(Vector3d.Zero, 1.0);
        world.AddParticle(new Vector3d(1.1, 0, 0), new Vector3d(0.1, -0.2, 0.3), 0.5);
        world.AddParticle(new Vector3d(1.0, 0.9, 0.2), 2.0);
        foreach (var generator in generators(world))
        {
            world.AddForce(generator);
        }

        return world;
    }

    private static SpringNetwork Springs(ParticleWorld world)
    {
        var springs = new SpringNetwork(world);
        springs.Add(0, 1, 40.0, 1.0, 0.3);
        springs.Add(1, 2, 25.0, 1.0, 0.1);
        return springs;
    }
}
