using System;
using System.IO;
using System.Linq;
using System.Text;
using System.Text.Json;
using ParticlePhysics.Contacts;
using ParticlePhysics.Demo.Animation;
using ParticlePhysics.Demo.Running;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Tests.Demo;

/// <summary>
/// The replay's scene as plain data: it reads the radii and the obstacles of a world's contact sets as the core
/// describes them (against hand-worked axes), and the page carries radii, links of every kind and colliders (with
/// a moving one's velocity) as the renderer reads them.
/// </summary>
public sealed class ReplaySceneTests
{
    [Fact]
    public void The_scene_reads_radii_and_every_obstacle_of_a_contact_set_as_the_core_describes_it()
    {
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(0, 1, 0), 1);
        world.AddParticle(new Vector3d(1, 1, 0), 1);
        world.SetRadius(1, 0.05);
        var box = new BoxObstacle(new Vector3d(3, 0, 0), new Vector3d(0.5, 1, 2));
        box.SetOrientation(new Vector3d(0, 0, -1), new Vector3d(0, 1, 0)); // a quarter turn about +y
        var sphere = new SphereObstacle(new Vector3d(0, -1, 0), 0.3) { Velocity = new Vector3d(0, 0, 2), ReferenceTime = 1 };
        var contacts = new ContactSet();
        contacts.Add(PlaneObstacle.Ground());
        contacts.Add(sphere);
        contacts.Add(new CapsuleObstacle(new Vector3d(0, 0, 0), new Vector3d(3, 4, 0), 0.25));
        contacts.Add(box);
        world.AddConstraints(contacts);

        var scene = SceneReader.Read(world);

        Assert.Equal(new[] { 0, 0.05 }, scene.Radii);
        Assert.Equal(new[] { ObstacleKind.Plane, ObstacleKind.Sphere, ObstacleKind.Capsule, ObstacleKind.Box }, scene.Colliders.Select(c => c.Shape.Kind));
        AssertClose(new Vector3d(0, 1, 0), scene.Colliders[0].Shape.AxisY); // the plane's normal
        // The moving sphere is where it is at t = 0 (1 s before its reference time, at 2 m/s along z), with its velocity.
        AssertClose(new Vector3d(0, -1, -2), scene.Colliders[1].Shape.Center);
        Assert.Equal(new Vector3d(0, 0, 2), scene.Colliders[1].Velocity);
        Assert.Equal(0.3, scene.Colliders[1].Shape.Radius);
        var capsule = scene.Colliders[2].Shape;
        AssertClose(new Vector3d(1.5, 2, 0), capsule.Center);
        AssertClose(new Vector3d(0.6, 0.8, 0), capsule.AxisY);
        Assert.Equal(2.5, capsule.HalfExtents.Y, 12);
        Assert.Equal(0.25, capsule.Radius);
        var turned = scene.Colliders[3].Shape;
        AssertClose(new Vector3d(0, 0, -1), turned.AxisX);
        AssertClose(new Vector3d(0, 1, 0), turned.AxisY);
        AssertClose(new Vector3d(1, 0, 0), turned.AxisZ);
        Assert.Equal(new Vector3d(0.5, 1, 2), turned.HalfExtents);
        Assert.All(scene.Colliders.Where(c => c.Shape.Kind != ObstacleKind.Sphere), c => Assert.Equal(Vector3d.Zero, c.Velocity));
    }

    [Fact]
    public void A_mesh_cloths_membrane_triangles_are_its_surface()
    {
        var flag = ParticlePhysics.Scenes.Scene.Load(Path.Combine(Engine.ReadmeExamplesTests.RepositoryRoot(), "samples", "scenes", "flag.json"));
        var scene = SceneReader.Read(flag.Build());
        Assert.Equal(2 * 12 * 8, scene.Triangles.Count / 3);
    }

    [Fact]
    public void The_drape_scene_has_its_sphere_and_the_radius_of_every_particle()
    {
        var drape = new DrapeScenario();
        var n = drape.Cloth.ParticlesPerSide;

        var scene = SceneReader.Read(drape.Build(), n);

        var collider = Assert.Single(scene.Colliders);
        Assert.Equal(ObstacleKind.Sphere, collider.Shape.Kind);
        Assert.Equal(drape.SphereCenter, collider.Shape.Center);
        Assert.Equal(drape.SphereRadius, collider.Shape.Radius);
        Assert.All(scene.Radii, r => Assert.Equal(drape.Radius, r));
        Assert.Empty(scene.Pinned); // the drape pins nothing by default
        Assert.Equal(2 * (n - 1) * (n - 1), scene.Triangles.Count / 3);
    }

    [Fact]
    public void The_page_carries_radii_links_of_every_kind_and_colliders()
    {
        var world = new ParticleWorld();
        world.AddParticle(Vector3d.Zero, 1);
        world.AddParticle(new Vector3d(1, 0, 0), 1);
        var setup = new ParticleSetup("two", () => world, 2, exact: null) { TableColumnList = new[] { "t", "energy" } };
        var plan = new RunPlan("rk4", 0.5, 2, 1, 1e-8);
        var recorder = new ReplayRecorder(setup, setup.ParticleCount, plan);
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
        scene.AddCollider(new SphereObstacle(new Vector3d(0, -1, 0), 0.5).Shape, new Vector3d(1, 0, 0));
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
        Assert.Equal(new[] { 1.0, 0, 0 }, sphere.GetProperty("velocity").EnumerateArray().Select(e => e.GetDouble()));
        Assert.Equal(new[] { 0, 0.5, 1 }, data.GetProperty("times").EnumerateArray().Select(e => e.GetDouble()));
        Assert.Equal("completed", data.GetProperty("status").GetString());
    }

    private static void AssertClose(Vector3d expected, Vector3d actual) =>
        Assert.True((expected - actual).Length < 1e-12, $"expected {expected}, got {actual}");
}
