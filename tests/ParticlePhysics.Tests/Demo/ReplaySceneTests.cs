using System;
using System.IO;
using System.Linq;
using System.Text;
using System.Text.Json;
using ParticlePhysics.Demo.Animation;
using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Tests.Demo;

/// <summary>
/// The replay's scene as plain data: each collider factory gives the shape a physics engine means (against
/// hand-worked axes), and the page carries radii, links of every kind and colliders as the renderer reads them.
/// </summary>
public sealed class ReplaySceneTests
{
    [Fact]
    public void A_box_turned_by_a_quaternion_has_the_rotated_axes()
    {
        // A quarter turn about +y: x goes to -z, z goes to +x.
        var half = Math.Sqrt(0.5);
        var box = ColliderShape.Box(new Vector3d(1, 2, 3), new Vector3d(0.5, 1, 2), half, 0, half, 0);

        AssertClose(new Vector3d(0, 0, -1), box.AxisX);
        AssertClose(new Vector3d(0, 1, 0), box.AxisY);
        AssertClose(new Vector3d(1, 0, 0), box.AxisZ);
        Assert.Equal(ColliderKind.Box, box.Kind);
        Assert.Equal(new Vector3d(0.5, 1, 2), box.HalfExtents);
    }

    [Fact]
    public void A_capsule_from_a_segment_is_centred_on_it_along_its_local_y()
    {
        var capsule = ColliderShape.Capsule(new Vector3d(0, 0, 0), new Vector3d(3, 4, 0), 0.25);

        Assert.Equal(new Vector3d(1.5, 2, 0), capsule.Center);
        AssertClose(new Vector3d(0.6, 0.8, 0), capsule.AxisY);
        Assert.Equal(2.5, capsule.HalfExtents.Y);
        Assert.Equal(0.25, capsule.Radius);
        Assert.Equal(0, Vector3d.Dot(capsule.AxisX, capsule.AxisY), 12);
        Assert.Equal(0, Vector3d.Dot(capsule.AxisZ, capsule.AxisY), 12);
        Assert.Equal(0, Vector3d.Dot(capsule.AxisX, capsule.AxisZ), 12);
    }

    [Fact]
    public void A_plane_keeps_a_unit_normal_and_a_zero_normal_is_refused()
    {
        AssertClose(new Vector3d(0, 1, 0), ColliderShape.Plane(Vector3d.Zero, new Vector3d(0, 5, 0)).Normal);
        var error = Assert.Throws<ArgumentException>(() => ColliderShape.Plane(Vector3d.Zero, Vector3d.Zero));
        Assert.Equal("normal", error.ParamName);
    }

    [Fact]
    public void The_page_carries_radii_links_of_every_kind_and_colliders()
    {
        var world = new ParticleWorld();
        world.AddParticle(Vector3d.Zero, 1);
        world.AddParticle(new Vector3d(1, 0, 0), 1);
        var setup = new ParticleSetup("two", () => world, 2, exact: null) { TableColumnList = new[] { "t", "energy" } };
        var plan = new RunPlan("rk4", 0.5, 2, 1, 1e-8);
        var recorder = new ReplayRecorder(setup, plan);
        var row = new double[setup.Columns.Count];
        row[4] = 1; // x1
        foreach (var step in Enumerable.Range(0, 3))
        {
            row[0] = step * 0.5;
            Assert.True(recorder.Wants(step));
            recorder.Add(step, row);
        }

        recorder.Finish(new RunOutcome(row, 2, 1.0, null, null));
        var scene = new ReplayScene(2);
        scene.SetRadius(1, 0.1);
        scene.Pin(0);
        scene.AddLink(0, 1, LinkKind.Rod, 1);
        scene.AddAnchoredLink(1, new Vector3d(0, 2, 0), LinkKind.Cable, 3);
        scene.AddLink(1, 0, LinkKind.Spring);
        scene.AddCollider(ColliderShape.Sphere(new Vector3d(0, -1, 0), 0.5));
        using var page = new MemoryStream();

        ReplayPage.Write(page, scene, recorder, "two <particles>", "a test", "final state");

        var html = Encoding.UTF8.GetString(page.ToArray());
        Assert.Contains("<title>two &lt;particles&gt;</title>", html, StringComparison.Ordinal);
        var start = html.IndexOf("id=\"replay-data\">", StringComparison.Ordinal) + "id=\"replay-data\">".Length;
        var data = JsonDocument.Parse(html[start..html.IndexOf("</script>", start, StringComparison.Ordinal)]).RootElement;
        Assert.Equal("two \u003Cparticles\u003E", data.GetProperty("title").GetString()); // escaped in the page, read back whole
        Assert.Equal(new[] { 0, 0.1 }, data.GetProperty("radii").EnumerateArray().Select(e => e.GetDouble()));
        Assert.Equal(new[] { 0 }, data.GetProperty("pinned").EnumerateArray().Select(e => e.GetInt32()));
        var links = data.GetProperty("links");
        Assert.Equal(new[] { 0, 1 }, links.GetProperty("rod").EnumerateArray().Select(e => e.GetInt32()));
        Assert.Equal(new[] { 1, 2 }, links.GetProperty("cable").EnumerateArray().Select(e => e.GetInt32())); // node 2 = anchor 0
        Assert.Equal(new[] { 3.0 }, links.GetProperty("cableLengths").EnumerateArray().Select(e => e.GetDouble()));
        Assert.Equal(new[] { 1, 0 }, links.GetProperty("spring").EnumerateArray().Select(e => e.GetInt32()));
        var sphere = data.GetProperty("colliders")[0];
        Assert.Equal("sphere", sphere.GetProperty("kind").GetString());
        Assert.Equal(0.5, sphere.GetProperty("radius").GetDouble());
        Assert.Equal(new[] { 0.0, -1, 0 }, sphere.GetProperty("center").EnumerateArray().Select(e => e.GetDouble()));
        Assert.Equal(3, sphere.GetProperty("axes").GetArrayLength());
        Assert.Equal(new[] { 0, 0.5, 1 }, data.GetProperty("times").EnumerateArray().Select(e => e.GetDouble()));
        Assert.Equal("completed", data.GetProperty("status").GetString());
    }

    private static void AssertClose(Vector3d expected, Vector3d actual) =>
        Assert.True((expected - actual).Length < 1e-12, $"expected {expected}, got {actual}");
}
