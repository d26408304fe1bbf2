using System;
using ParticlePhysics.Forces;
using ParticlePhysics.Parallel;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Parallel;

/// <summary>
/// The spring network's Jacobian product (<see cref="SpringJacobianProduct"/>): on one thread against the directional
/// derivative of the forces, and over any number of parts, on any runner, with the one-thread bits.
/// </summary>
public class SpringJacobianProductTests
{
    private const double H = 1.0 / 60;

    [Fact]
    public void The_product_is_the_directional_derivative_of_the_forces()
    {
        // Stretched springs without damping: the linearisation is exact (no transverse clamp, no velocity term), so
        // K w = (f(x + e w) - f(x - e w)) / 2 e up to e^2 (an oracle that knows nothing of the Jacobian's code).
        var world = RandomNetwork(seed: 3, particles: 1500, springs: 5000, damping: 0.0, out var springs);
        ILinearizableSystem system = world;
        var n = world.CoordinateCount;
        var x = world.Positions.ToArray();
        var v = world.Velocities.ToArray();
        var w = Disturbance(n);
        system.Linearize(0.0, x, v, 1.0, 0.0, UserForceTreatment.Explicit, new double[n]);
        var product = new double[n];
        springs.AddJacobianProduct(w, product);

        const double e = 1e-5;
        var plus = new double[n];
        var minus = new double[n];
        for (var k = 0; k < n; k++)
        {
            plus[k] = x[k] + (e * w[k]);
            minus[k] = x[k] - (e * w[k]);
        }

        var forcesPlus = new double[n];
        var forcesMinus = new double[n];
        var masses = world.Masses.ToArray();
        var inverseMasses = world.InverseMasses.ToArray();
        springs.AddForces(new ParticleState(0.0, plus, v, masses, inverseMasses), forcesPlus);
        springs.AddForces(new ParticleState(0.0, minus, v, masses, inverseMasses), forcesMinus);
        var largest = 0.0;
        for (var k = 0; k < n; k++)
        {
            largest = Math.Max(largest, Math.Abs(product[k]));
            Assert.Equal((forcesPlus[k] - forcesMinus[k]) / (2 * e), product[k], 1e-5 * (1.0 + Math.Abs(product[k])));
        }

        Assert.True(largest > 1.0, $"the product is not trivial: largest component {largest}");
    }

    [Theory]
    [InlineData(2)]
    [InlineData(3)]
    [InlineData(4)]
    [InlineData(5)]
    [InlineData(16)]
    public void Any_number_of_parts_on_any_runner_gives_the_bits_of_one_thread(int parallelism)
    {
        // Springs in random order (ends in either order, a particle's springs scattered over the list, repeated
        // pairs): the parts' segments are short and every kind of segment occurs. The runner's parallelism sets the
        // parts (two per thread); a sequential runner in reverse order and real threads must both give the one-thread
        // bits.
        var expected = Product(RandomNetwork(7, 1200, 6000, 0.3, out _), null);
        var reversed = Product(RandomNetwork(7, 1200, 6000, 0.3, out _), new ReverseRunner(parallelism));
        Assert.Equal(StateMetrics.BitHash(expected), StateMetrics.BitHash(reversed));
        if (parallelism <= 3)
        {
            using var threads = new WorkerThreadRunner(parallelism);
            var threaded = Product(RandomNetwork(7, 1200, 6000, 0.3, out _), threads);
            Assert.Equal(StateMetrics.BitHash(expected), StateMetrics.BitHash(threaded));
        }
    }

    [Fact]
    public void On_a_cloth_the_parts_compute_few_springs_twice()
    {
        // The 64 x 64 cloth on two threads: four parts of 1024 particles (16 rows), so three boundaries, each crossed
        // by the springs of about two rows (the bend springs reach two rows down).
        var cloth = new ClothScenario { Resolution = 1.0 / 63 }.Build();
        using var runner = new WorkerThreadRunner(2);
        cloth.Runner = runner;
        var springs = Springs(cloth);
        _ = Product(cloth, runner);
        var product = springs.ParallelProduct!;
        Assert.Equal(4, product.Parts);
        var extra = product.SpringsComputed - springs.Count;
        Assert.InRange(extra, 1, 3 * 6 * 64);
    }

    /// <summary>J w after a linearisation at h, with the world's runner set to <paramref name="runner"/>.</summary>
    private static double[] Product(ParticleWorld world, IParallelRunner? runner)
    {
        world.Runner = runner;
        ILinearizableSystem system = world;
        var n = world.CoordinateCount;
        system.Linearize(0.0, world.Positions, world.Velocities, H * H, H, UserForceTreatment.Explicit, new double[n]);
        var product = new double[n];
        Springs(world).AddJacobianProduct(Disturbance(n), product);
        return product;
    }

    private static SpringNetwork Springs(ParticleWorld world)
    {
        foreach (var force in world.Forces)
        {
            if (force is SpringNetwork springs)
            {
                return springs;
            }
        }

        throw new InvalidOperationException("no spring network");
    }

    /// <summary>A vector that is not smooth, so that every spring's term differs.</summary>
    private static double[] Disturbance(int n)
    {
        var w = new double[n];
        for (var k = 0; k < n; k++)
        {
            w[k] = Math.Sin(1.7 * k) + (0.25 * (k % 7));
        }

        return w;
    }

    /// <summary>Particles in a unit cube, springs between random pairs with rest lengths below their lengths (stretched).</summary>
    private static ParticleWorld RandomNetwork(int seed, int particles, int springs, double damping, out SpringNetwork network)
    {
        var random = new Random(seed);
        var world = new ParticleWorld();
        for (var i = 0; i < particles; i++)
        {
            world.AddParticle(
                new Vector3d(random.NextDouble(), random.NextDouble(), random.NextDouble()),
                new Vector3d(random.NextDouble() - 0.5, random.NextDouble() - 0.5, random.NextDouble() - 0.5),
                0.5 + random.NextDouble());
        }

        network = new SpringNetwork(world);
        for (var s = 0; s < springs; s++)
        {
            int a = random.Next(particles), b = random.Next(particles - 1);
            b = b >= a ? b + 1 : b;
            if (s % 97 == 0 && s > 0)
            {
                var (first, second) = network.GetEnds(s - 1);
                (a, b) = (second, first); // a repeated pair, the other way round
            }

            var length = (world.GetPosition(a) - world.GetPosition(b)).Length;
            network.Add(a, b, 10.0 + (40.0 * random.NextDouble()), 0.5 * length * random.NextDouble(), damping * random.NextDouble());
        }

        world.AddForce(network);
        return world;
    }

    /// <summary>A runner of the given parallelism that runs the chunks one at a time, last first.</summary>
    private sealed class ReverseRunner : IParallelRunner
    {
        public ReverseRunner(int parallelism) => MaxParallelism = parallelism;

        public int MaxParallelism { get; }

        public void Run(IParallelWork work, int chunkCount)
        {
            for (var c = chunkCount - 1; c >= 0; c--)
            {
                work.Execute(c, chunkCount);
            }
        }
    }
}
