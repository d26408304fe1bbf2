using System;
using System.IO;
using System.Runtime.InteropServices;
using ParticlePhysics.Cloth;
using ParticlePhysics.Driver;
using ParticlePhysics.Integrators;
using ParticlePhysics.Snapshots;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Packaging;

/// <summary>
/// The calls docs/unity.md makes, in the same order, with a stand-in for UnityEngine.Vector3 (three floats x, y, z):
/// Unity is not here to compile the page itself.
/// </summary>
[Collection(AllocationMeasurements.Name)]
public class UnityUsageTests
{
    [Fact]
    public void The_documented_component_builds_steps_and_renders_a_cloth_without_allocating()
    {
        // Start()
        var builder = new ClothBuilder { Rows = 21, Columns = 21, Spacing = 0.05f, TotalMass = 1 };
        builder.WithSprings(50f, 0.05f);
        var cloth = builder.Build();
        var driver = new FixedTimestepDriver(cloth.System, new SemiImplicitEuler(), fixedTimeStep: 1.0 / 60, subSteps: 16);
        var vertices = new UnityVector3[cloth.ParticleCount];
        var normals = new UnityVector3[cloth.ParticleCount];
        var triangles = cloth.Mesh.CreateTriangles();
        Assert.Equal(6 * 20 * 20, triangles.Length);
        WriteMesh(driver, cloth, vertices, normals);

        // Update() at uneven frame times: after the first step (which sizes the scratch buffers), no allocation; a
        // hanging cloth with unit normals.
        driver.Advance(0.02);
        WriteMesh(driver, cloth, vertices, normals);
        var before = GC.GetAllocatedBytesForCurrentThread();
        for (var frame = 0; frame < 120; frame++)
        {
            driver.Advance(frame % 3 == 0 ? 0.021 : 0.013);
            WriteMesh(driver, cloth, vertices, normals);
        }

        Assert.Equal(0, GC.GetAllocatedBytesForCurrentThread() - before);
        Assert.True(vertices[cloth.ParticleCount - 1].Y < -0.5f, $"the free corner hangs: y = {vertices[^1].Y}");
        Assert.All(normals, n => Assert.Equal(1f, MathF.Sqrt((n.X * n.X) + (n.Y * n.Y) + (n.Z * n.Z)), 5));

        // The save game.
        var file = new MemoryStream();
        SimulationSnapshot.Capture(cloth.System, driver.Integrator).WriteTo(file);
        driver.Advance(0.5);
        file.Position = 0;
        SimulationSnapshot.ReadFrom(file).RestoreTo(cloth.System, driver.Integrator);
        driver.Reset();
        Assert.Equal(0.0, driver.InterpolationFactor);
    }

    private static void WriteMesh(FixedTimestepDriver driver, ParticleCloth cloth, UnityVector3[] vertices, UnityVector3[] normals)
    {
        var v = MemoryMarshal.Cast<UnityVector3, System.Numerics.Vector3>(vertices.AsSpan());
        var n = MemoryMarshal.Cast<UnityVector3, System.Numerics.Vector3>(normals.AsSpan());
        driver.InterpolatePositions(cloth.FirstParticle, cloth.ParticleCount, v);
        cloth.Mesh.ComputeNormals(v, n);
    }

    /// <summary>UnityEngine.Vector3's layout: three public floats, sequential.</summary>
    [StructLayout(LayoutKind.Sequential)]
    private struct UnityVector3
    {
        public float X;
        public float Y;
        public float Z;
    }
}
