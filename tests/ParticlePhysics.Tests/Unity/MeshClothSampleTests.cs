using System;
using System.Linq;
using System.Linq.Expressions;
using ParticlePhysics.Cloth;
using ParticlePhysics.Constraints;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Unity;

/// <summary>
/// The Unity <c>MeshCloth</c> sample, compiled with Unity's settings and run on the stand-in UnityEngine: it takes the
/// MeshFilter's mesh (a flag cut along a UV seam), welds the seam, pins the vertices painted red, attaches them to a
/// transform and follows it, and writes positions and normals back each frame without allocating.
/// </summary>
[Collection(AllocationMeasurements.Name)]
public class MeshClothSampleTests
{
    private const int Columns = 8, Rows = 6, Seam = 4;

    [Fact]
    public void The_sample_compiles_with_unity_settings_without_errors_or_warnings()
    {
        var (image, diagnostics) = UnityScripts.Compile(
            "Assembly-CSharp", new[] { (UnityScripts.MeshClothPath, UnityScripts.ReadRepositoryFile(UnityScripts.MeshClothPath)) });
        Assert.True(diagnostics.IsEmpty, UnityScripts.Describe(diagnostics));
        Assert.NotNull(image);
    }

    [Fact]
    public void The_sample_welds_pins_by_colour_follows_its_anchor_and_writes_the_mesh_without_allocating()
    {
        object? anchor = null;
        using var player = new UnityPlayer(sample => anchor = Prepare(sample), "MeshCloth", UnityScripts.MeshClothImage);
        player.RunFrame(0f);   // Start
        var cloth = (TriangleCloth)player.SampleType.GetProperty("Simulation")!.GetValue(player.Sample)!;
        var body = (KinematicBody)player.SampleType.GetProperty("Body")!.GetValue(player.Sample)!;
        var vertexCount = 2 * (Seam + 1) * (Rows + 1);
        Assert.Equal(vertexCount, cloth.Mesh.VertexCount);
        Assert.Equal((Columns + 1) * (Rows + 1), cloth.ParticleCount); // the seam's column welded
        Assert.Equal(Rows + 1, body.Particles.Count); // the red pole vertices
        Assert.Equal(2 * Columns * Rows * 3, player.MeshProperty<int[]>("triangles").Length);

        // Frames of uneven length, the anchor rising: nothing allocated after the first step.
        player.RunFrame(0.02f);
        // The anchor's positions boxed beforehand and set through a compiled setter: the test itself allocates nothing.
        var position = anchor!.GetType().GetProperty("position")!;
        var target = Expression.Parameter(typeof(object));
        var value = Expression.Parameter(typeof(object));
        var setter = Expression.Lambda<Action<object, object>>(
            Expression.Call(Expression.Convert(target, anchor.GetType()), position.SetMethod!, Expression.Unbox(value, position.PropertyType)),
            target,
            value).Compile();
        var poses = Enumerable.Range(0, 90).Select(frame => Activator.CreateInstance(position.PropertyType, 0f, 0.002f * frame, 0f)!).ToArray();
        Assert.Equal(0, ThreadAllocations.Measure(() =>
        {
            for (var frame = 0; frame < 90; frame++)
            {
                setter(anchor, poses[frame]);
                player.RunFrame(frame % 3 == 0 ? 0.021f : 0.013f);
            }
        }));
        Assert.True(player.Enabled, player.Errors);
        Assert.Equal(string.Empty, player.Errors);

        // The pole followed the anchor up by 0.178 m (the body's pose at the end of the last frame, reached when the
        // driver has stepped that time: within one step's motion).
        var pole = cloth.System.GetPosition(cloth.ParticleIndex(0));
        Assert.InRange(pole.Y, 1.5 + 0.178 - 0.01, 1.5 + 0.178 + 0.001);

        // The seam's two render vertices have one position and one normal; the free edge hangs below the pole.
        var vertices = player.MeshProperty<Array>("vertices");
        var normals = player.MeshProperty<Array>("normals");
        Assert.Equal(vertexCount, vertices.Length);
        for (var r = 0; r <= Rows; r++)
        {
            int left = (r * (Seam + 1)) + Seam, right = ((Seam + 1) * (Rows + 1)) + (r * (Seam + 1));
            Assert.Equal(Floats(vertices.GetValue(left)!), Floats(vertices.GetValue(right)!));
            Assert.Equal(Floats(normals.GetValue(left)!), Floats(normals.GetValue(right)!));
        }

        var tip = Floats(vertices.GetValue(vertexCount - 1)!);
        Assert.True(tip.Y < pole.Y - 0.2, $"the free corner hangs: y = {tip.Y}, pole at {pole.Y}");
        foreach (var normal in normals)
        {
            var n = Floats(normal!);
            Assert.Equal(1f, MathF.Sqrt((n.X * n.X) + (n.Y * n.Y) + (n.Z * n.Z)), 5);
        }
    }

    /// <summary>
    /// Gives the sample's MeshFilter a flag of Columns x Rows cells of 0.1 m in the plane z = 0 from y = 1.5 down, cut
    /// along column Seam into two halves whose seam vertices are repeated (a UV seam), the pole column painted red; and
    /// an anchor transform at the origin. Returns the anchor.
    /// </summary>
    private static object Prepare(object sample)
    {
        var unity = sample.GetType().BaseType!.Assembly;
        var gameObject = sample.GetType().GetProperty("gameObject")!.GetValue(sample)!;
        var vector3 = unity.GetType("UnityEngine.Vector3", throwOnError: true)!;
        var color = unity.GetType("UnityEngine.Color", throwOnError: true)!;
        var meshType = unity.GetType("UnityEngine.Mesh", throwOnError: true)!;
        var filterType = unity.GetType("UnityEngine.MeshFilter", throwOnError: true)!;
        var count = 2 * (Seam + 1) * (Rows + 1);
        var vertices = Array.CreateInstance(vector3, count);
        var colors = Array.CreateInstance(color, count);
        var triangles = new System.Collections.Generic.List<int>();
        var k = 0;
        foreach (var (first, last) in new[] { (0, Seam), (Seam, Columns) })
        {
            var start = k;
            for (var r = 0; r <= Rows; r++)
            {
                for (var c = first; c <= last; c++)
                {
                    vertices.SetValue(Activator.CreateInstance(vector3, 0.1f * c, 1.5f - (0.1f * r), 0f), k);
                    colors.SetValue(Activator.CreateInstance(color, c == 0 ? 1f : 0f, 0f, 0f, 1f), k++);
                }
            }

            var width = last - first + 1;
            for (var r = 0; r < Rows; r++)
            {
                for (var c = 0; c + 1 < width; c++)
                {
                    int a = start + (r * width) + c, b = a + 1, d = a + width, e = d + 1;
                    triangles.AddRange(new[] { a, d, b, b, d, e });
                }
            }
        }

        var mesh = Activator.CreateInstance(meshType)!;
        meshType.GetMethod("SetVertices", new[] { vertices.GetType() })!.Invoke(mesh, new object[] { vertices });
        meshType.GetMethod("SetTriangles", new[] { typeof(int[]), typeof(int) })!.Invoke(mesh, new object[] { triangles.ToArray(), 0 });
        meshType.GetProperty("colors")!.SetValue(mesh, colors);
        var filter = gameObject.GetType().GetMethod("GetComponent")!.MakeGenericMethod(filterType).Invoke(gameObject, null)!;
        filterType.GetProperty("sharedMesh")!.SetValue(filter, mesh);

        var anchorObject = Activator.CreateInstance(gameObject.GetType(), "Anchor")!;
        var anchor = anchorObject.GetType().GetProperty("transform")!.GetValue(anchorObject)!;
        sample.GetType().GetField("anchor")!.SetValue(sample, anchor);
        return anchor;
    }

    private static (float X, float Y, float Z) Floats(object vector) =>
        ((float)vector.GetType().GetField("x")!.GetValue(vector)!, (float)vector.GetType().GetField("y")!.GetValue(vector)!, (float)vector.GetType().GetField("z")!.GetValue(vector)!);
}
