using System;
using System.Linq;
using ParticlePhysics.Cloth;
using ParticlePhysics.Constraints;
using ParticlePhysics.Integrators;
using ParticlePhysics.Parallel;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Engine;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Cloth;

/// <summary>
/// The cloth from a mesh: the course's grid is one case of it (the same rows as <see cref="ClothBuilder"/>), pins and
/// attachment by vertex, every integrator, no allocation per step, and the same bits on one core and two.
/// </summary>
[Collection(AllocationMeasurements.Name)]
public class MeshClothBuilderTests
{
    [Theory]
    [MemberData(nameof(DeterminismAndAllocationTests.Integrators), MemberType = typeof(DeterminismAndAllocationTests))]
    public void The_course_cloth_built_through_the_mesh_gives_the_same_rows_as_the_cloth_builder(string integrator)
    {
        var scenario = new ClothScenario();
        var expected = scenario.Build();
        var actual = CourseClothFromMesh(scenario.ParticlesPerSide, scenario.Resolution).System;
        var a = IntegratorCatalog.Create(integrator);
        var b = IntegratorCatalog.Create(integrator);
        for (var s = 0; s < 50; s++)
        {
            expected.Step(a, ClothScenario.DefaultTimeStep);
            actual.Step(b, ClothScenario.DefaultTimeStep);
            Assert.Equal(StateMetrics.BitHash(expected.State), StateMetrics.BitHash(actual.State));
        }
    }

    [Fact]
    public void Pinned_vertices_hold_and_attached_vertices_follow_their_body()
    {
        var (vertices, triangles) = ClothMeshes.Strip(6, 6, 0.1, 0.1);
        var builder = new MeshClothBuilder(new WeldedMesh(vertices, triangles)) { BendingRigidity = 1e-4 };
        builder.Pin(48);
        var cloth = builder.Build();
        var world = cloth.System;
        var body = new KinematicBody(world, Vector3d.Zero, Rotation3d.Identity);
        cloth.Attach(body, new[] { 0, 1, 2, 2 });
        Assert.Equal(new[] { 0, 1, 2 }, body.Particles.ToArray());
        var stepper = new ImplicitEuler();
        var pinned = world.GetPosition(cloth.ParticleIndex(48));
        for (var frame = 0; frame < 30; frame++)
        {
            body.MoveTo(new Vector3d(0, 0.01 * (frame + 1), 0), Rotation3d.Identity, 1.0 / 60);
            world.Step(stepper, 1.0 / 60);
        }

        Assert.Equal(pinned, world.GetPosition(cloth.ParticleIndex(48)));
        for (var v = 0; v < 3; v++)
        {
            var p = world.GetPosition(cloth.ParticleIndex(v));
            Assert.Equal(0.3, p.Y, 12);
            Assert.Equal(vertices[(3 * v) + 2], p.Z, 12);
        }

        Assert.True(world.GetPosition(cloth.ParticleIndex(24)).Y < 0.3, "the free middle of the cloth does not hang");
    }

    [Theory]
    [MemberData(nameof(DeterminismAndAllocationTests.Integrators), MemberType = typeof(DeterminismAndAllocationTests))]
    public void A_membrane_cloth_with_bending_steps_without_allocating_and_repeats_bit_for_bit(string integrator)
    {
        var cloth = Curtain();
        var stepper = IntegratorCatalog.Create(integrator);
        StateMetrics.Run(cloth.System, stepper, 0.001, 3);
        var steps = 3;
        var allocated = ThreadAllocations.Measure(() =>
        {
            StateMetrics.Run(cloth.System, stepper, 0.001, 20);
            steps += 20;
        });
        Assert.Equal(0, allocated);

        var again = Curtain();
        StateMetrics.Run(again.System, IntegratorCatalog.Create(integrator), 0.001, steps);
        Assert.Equal(StateMetrics.BitHash(cloth.System.State), StateMetrics.BitHash(again.System.State));
    }

    [Theory]
    [InlineData("implicit-euler")]
    [InlineData("xpbd")]
    public void Two_threads_give_the_same_bits_as_one(string integrator)
    {
        var one = LargeCurtain();
        var two = LargeCurtain();
        using var runner = new WorkerThreadRunner(2);
        two.System.Runner = runner;
        var a = IntegratorCatalog.Create(integrator);
        var b = IntegratorCatalog.Create(integrator);
        for (var s = 0; s < 5; s++)
        {
            one.System.Step(a, 1.0 / 60);
            two.System.Step(b, 1.0 / 60);
        }

        Assert.Equal(StateMetrics.BitHash(one.System.State), StateMetrics.BitHash(two.System.State));
    }

    /// <summary>The course's cloth (<see cref="ClothBuilder"/>'s springs and order) through the mesh path.</summary>
    internal static TriangleCloth CourseClothFromMesh(int n, double r)
    {
        var vertices = new double[3 * n * n];
        for (var row = 0; row < n; row++)
        {
            for (var col = 0; col < n; col++)
            {
                vertices[3 * ((row * n) + col)] = col * r;
                vertices[(3 * ((row * n) + col)) + 2] = row * r;
            }
        }

        var builder = new MeshClothBuilder(new WeldedMesh(vertices, new ClothMesh(n, n).CreateTriangles()))
        {
            Stretch = ClothStretch.None,
            MassDistribution = ClothMassDistribution.Uniform,
            TotalMass = 1,
            Drag = 0.01,
        };
        builder.Pin(0).Pin(n - 1);
        var diagonal = r * Math.Sqrt(2);
        for (var row = 0; row < n; row++)
        {
            for (var col = 0; col < n; col++)
            {
                var i = (row * n) + col;
                if (col + 1 < n)
                {
                    builder.AddSpring(i, i + 1, 50, 0.05, r);
                }

                if (row + 1 < n)
                {
                    builder.AddSpring(i, i + n, 50, 0.05, r);
                }

                if (row + 1 < n && col + 1 < n)
                {
                    builder.AddSpring(i, i + n + 1, 50, 0.05, diagonal);
                    builder.AddSpring(i + 1, i + n, 50, 0.05, diagonal);
                }

                if (col + 2 < n)
                {
                    builder.AddSpring(i, i + 2, 50, 0.05, 2 * r);
                }

                if (row + 2 < n)
                {
                    builder.AddSpring(i, i + (2 * n), 50, 0.05, 2 * r);
                }
            }
        }

        return builder.Build();
    }

    /// <summary>A 12 x 12-cell curtain of membrane and bending, pinned along its top, soft enough for the explicit integrators at 1 ms.</summary>
    private static TriangleCloth Curtain()
    {
        var (vertices, triangles) = ClothMeshes.Strip(12, 12, 0.05, 0.05);
        var builder = new MeshClothBuilder(new WeldedMesh(vertices, triangles)) { Modulus = 20, BendingRigidity = 1e-4, AreaDensity = 0.2 };
        for (var j = 0; j <= 12; j++)
        {
            builder.Pin(j);
        }

        var cloth = builder.Build();
        cloth.System.SetPosition(cloth.ParticleIndex(13 * 12), new Vector3d(0.6, 0.05, 0)); // a corner lifted, so it moves
        return cloth;
    }

    /// <summary>A 90 x 90-cell curtain (16,200 triangles): large enough that the passes split over a runner.</summary>
    private static TriangleCloth LargeCurtain()
    {
        var (vertices, triangles) = ClothMeshes.Strip(90, 90, 0.01, 0.01);
        var builder = new MeshClothBuilder(new WeldedMesh(vertices, triangles)) { BendingRigidity = 1e-5, AreaDensity = 0.2 };
        for (var j = 0; j <= 90; j++)
        {
            builder.Pin(j);
        }

        return builder.Build();
    }
}
