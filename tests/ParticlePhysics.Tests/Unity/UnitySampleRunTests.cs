using System;
using System.IO;
using System.Linq;
using ParticlePhysics.Integrators;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Unity;

/// <summary>
/// The compiled Unity sample, run by the stand-in UnityEngine's frame loop: it builds its mesh in Start, hangs the cloth
/// from two corners in Update without allocating, and saves and restores bit for bit.
/// </summary>
[Collection(AllocationMeasurements.Name)]
public class UnitySampleRunTests
{
    [Fact]
    public void The_sample_hangs_its_cloth_and_updates_the_mesh_without_allocating()
    {
        using var player = new UnityPlayer();
        player.RunFrame(0f);   // Start
        var cloth = player.Cloth;
        var n = (int)player.GetField("particlesPerSide");
        Assert.Equal(21, n);
        Assert.Equal(n * n, cloth.ParticleCount);
        Assert.Equal(6 * (n - 1) * (n - 1), player.MeshProperty<int[]>("triangles").Length);
        Assert.IsType<ImplicitEuler>(player.Driver.Integrator);

        // The first step sizes the integrator's buffers; after it, uneven frames allocate nothing.
        player.RunFrame(0.02f);
        Assert.Equal(0, ThreadAllocations.Measure(() =>
        {
            for (var frame = 0; frame < 120; frame++)
            {
                player.RunFrame(frame % 3 == 0 ? 0.021f : 0.013f);
            }
        }));
        Assert.True(player.Enabled, player.Errors);
        Assert.Equal(string.Empty, player.Errors);

        // The mesh holds the interpolated positions (the free corner hangs) and unit normals.
        var vertices = player.MeshProperty<Array>("vertices");
        Assert.Equal(n * n, vertices.Length);
        var corner = (float)Component(vertices.GetValue(n * n - 1)!, "y");
        Assert.True(corner < -0.5f, $"the free corner hangs: y = {corner}");
        Assert.Equal(corner, (float)player.Driver.System.GetPosition(cloth.ParticleIndex(n - 1, n - 1)).Y, 2);
        foreach (var normal in player.MeshProperty<Array>("normals"))
        {
            var x = (float)Component(normal!, "x");
            var y = (float)Component(normal!, "y");
            var z = (float)Component(normal!, "z");
            Assert.Equal(1f, MathF.Sqrt((x * x) + (y * y) + (z * z)), 5);
        }
    }

    [Fact]
    public void Save_and_restore_give_the_bits_of_running_on()
    {
        using var player = new UnityPlayer();
        player.RunFrame(0f);
        for (var frame = 0; frame < 30; frame++)
        {
            player.RunFrame(1f / 60);
        }

        var save = new MemoryStream();
        player.Call("Save", save);
        for (var frame = 0; frame < 30; frame++)
        {
            player.RunFrame(1f / 60);
        }

        var straight = player.Cloth.System.State.ToArray();
        save.Position = 0;
        player.Call("Restore", save);
        for (var frame = 0; frame < 30; frame++)
        {
            player.RunFrame(1f / 60);
        }

        Assert.Equal(straight.Select(BitConverter.DoubleToInt64Bits), player.Cloth.System.State.ToArray().Select(BitConverter.DoubleToInt64Bits));

        // A truncated save throws and leaves the cloth as it was.
        var state = player.Cloth.System.State.ToArray();
        var truncated = new MemoryStream(save.ToArray()[..40]);
        var error = Assert.Throws<System.Reflection.TargetInvocationException>(() => player.Call("Restore", truncated));
        Assert.IsType<InvalidDataException>(error.InnerException);
        Assert.Equal(state, player.Cloth.System.State.ToArray());
    }

    [Fact]
    public void Moving_a_pinned_corner_carries_the_cloth()
    {
        using var player = new UnityPlayer();
        player.RunFrame(0f);
        var vector3 = player.Mesh.GetType().Assembly.GetType("UnityEngine.Vector3", throwOnError: true)!;
        var target = Activator.CreateInstance(vector3, 0.25f, 0.5f, -0.125f)!;
        player.Call("MoveParticle", 0, 0, target);
        var moved = player.Call("ParticlePosition", 0, 0);
        Assert.Equal((0.25f, 0.5f, -0.125f), ((float)Component(moved, "x"), (float)Component(moved, "y"), (float)Component(moved, "z")));
        for (var frame = 0; frame < 60; frame++)
        {
            player.RunFrame(1f / 60);
        }

        // Pinned: it stays where it was put.
        Assert.Equal(new Vector3d(0.25, 0.5, -0.125), player.Cloth.System.GetPosition(player.Cloth.ParticleIndex(0, 0)));
    }

    private static object Component(object vector, string name) => vector.GetType().GetField(name)!.GetValue(vector)!;
}
