using System;
using System.Globalization;
using System.IO;
using System.Linq;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenes;
using ParticlePhysics.Tests.Demo;
using ParticlePhysics.Tests.Engine;

namespace ParticlePhysics.Tests.Scenes;

/// <summary>The scene command on the sample scenes: every one runs, and the physics of the hand-made ones holds.</summary>
public class SceneRunTests
{
    private static readonly string _folder = Path.Combine(ReadmeExamplesTests.RepositoryRoot(), "samples", "scenes");
    private readonly Xunit.Abstractions.ITestOutputHelper _output;

    public SceneRunTests(Xunit.Abstractions.ITestOutputHelper output)
    {
        _output = output;
    }

    public static TheoryData<string> Samples()
    {
        var data = new TheoryData<string>();
        foreach (var file in Directory.GetFiles(_folder, "*.json").OrderBy(f => f, StringComparer.Ordinal))
        {
            data.Add(Path.GetFileName(file));
        }

        return data;
    }

    [Theory]
    [MemberData(nameof(Samples))]
    public void Every_sample_scene_validates_and_runs(string name)
    {
        var path = Path.Combine(_folder, name);
        var check = DemoProcess.Run("scene", "--validate", path);
        Assert.Equal(0, check.ExitCode);
        Assert.Equal($"{path}: valid", check.OutputLines[0]);
        Assert.StartsWith("particles: ", check.OutputLines[1], StringComparison.Ordinal);

        var run = DemoProcess.Run("scene", path, "--duration", "0.5");
        Assert.True(run.ExitCode == 0, run.Error);
        Assert.Equal(string.Empty, run.Error);
        Assert.StartsWith("final state at t = 0.5", run.OutputLines[^1], StringComparison.Ordinal);
    }

    [Fact]
    public void The_samples_include_every_kind_of_this_version()
    {
        var objects = new System.Collections.Generic.HashSet<string>();
        var colliders = new System.Collections.Generic.HashSet<string>();
        foreach (var file in Directory.GetFiles(_folder, "*.json"))
        {
            var scene = Scene.Load(file);
            objects.UnionWith(scene.ObjectKinds);
            colliders.UnionWith(scene.ColliderKinds);
        }

        Assert.Equal(new[] { "cables", "cloth", "granular", "load", "particles", "rigid", "rods", "rope", "soft", "springs" }, objects.OrderBy(k => k, StringComparer.Ordinal));
        Assert.Equal(new[] { "box", "capsule", "heightfield", "mesh", "plane", "sphere" }, colliders.OrderBy(k => k, StringComparer.Ordinal));
    }

    [Fact]
    public void The_flag_welds_its_seam_and_the_clamped_rope_sags_as_its_rigidity_says()
    {
        var flag = Scene.Load(Path.Combine(_folder, "flag.json"));
        Assert.Equal(13 * 9, flag.ParticleCount); // 7 x 9 + 7 x 9 vertices, the 9 of the seam welded
        var world = flag.Build();
        Assert.Equal(9, Enumerable.Range(0, world.Count).Count(world.IsPinned));
        Assert.Equal(0.005, world.GetRadius(0));

        var ropes = Scene.Load(Path.Combine(_folder, "ropes.json"));
        var rope = ropes.Build();
        var stepper = IntegratorCatalog.Create(ropes.Settings.Integrator);
        for (var s = 0; s < 200; s++)
        {
            rope.Step(stepper, ropes.Settings.TimeStep);
        }

        // mu g L^4 / (8 EI) with mu = 0.1 kg/m, EI = 2.5 N m^2, L = 1 m: 0.04905 m below the clamp's height.
        var sag = 1.0 - rope.GetPosition(20).Y;
        Assert.InRange(sag, 0.04905 * 0.98, 0.04905 * 1.02);
        Assert.True(rope.GetPosition(31).Y < 0.95, "the limp rope does not hang");
    }

    [Fact]
    public void Newtons_cradle_passes_the_momentum_along_the_row()
    {
        // Ball 0 swings down from 30 degrees and strikes the row at its lowest point, u = sqrt(2 g L (1 - cos 30)).
        // Just before, it carries all the row's momentum; just after, ball 4 does, at the same speed, and 0 to 3 are still.
        var (header, rows) = DemoProcess.Run("scene", Path.Combine(_folder, "newtons-cradle.json"), "--duration", "0.7", "--every", "1", "--format", "csv").Csv();
        double Column(double[] row, string name) => row[Array.IndexOf(header, name)];
        var impact = Array.FindIndex(rows, r => Column(r, "vx4") > 0); // the balls touch: the blow crosses the row within a step
        Assert.True(impact > 0, "ball 0 never reached the row");
        var before = rows[impact - 1];
        var after = rows[impact + 5];
        var u = Math.Sqrt(2 * 9.81 * (1 - Math.Cos(Math.PI / 6)));
        Assert.InRange(Column(before, "vx0"), 0.995 * u, 1.005 * u);
        double Momentum(double[] row) => Enumerable.Range(0, 5).Sum(i => 0.1 * Column(row, $"vx{i}"));
        Assert.InRange(Momentum(after), 0.99 * Momentum(before), 1.01 * Momentum(before));
        Assert.InRange(Column(after, "vx4"), 0.98 * u, 1.005 * u);
        for (var i = 0; i < 4; i++)
        {
            Assert.True(Math.Abs(Column(after, $"vx{i}")) < 0.01 * u, $"ball {i} still moves at {Column(after, $"vx{i}")} m/s");
        }
    }

    [Fact]
    public void The_rope_bridge_hangs_and_the_ball_pit_settles_inside_its_box()
    {
        var bridge = DemoProcess.Run("scene", Path.Combine(_folder, "rope-bridge.json"), "--format", "csv").Csv();
        var last = bridge.Rows[^1];
        var minY = last[Array.IndexOf(bridge.Header, "min_y")];
        Assert.InRange(minY, -1.0, -0.3); // 5 % of slack on a 4 m span sags about sqrt(3 L dL / 8) = 0.55 m, more under the load
        Assert.True(last[Array.IndexOf(bridge.Header, "max_speed")] < 0.5, "the bridge comes to rest");

        var pit = DemoProcess.Run("scene", Path.Combine(_folder, "ball-pit.json"), "--format", "csv").Csv();
        var end = pit.Rows[^1];
        var count = (int)end[Array.IndexOf(pit.Header, "particles")];
        for (var i = 0; i < count; i++)
        {
            double x = end[1 + (6 * i)], y = end[2 + (6 * i)], z = end[3 + (6 * i)];
            Assert.InRange(y, 0.05 - 1e-6, 2);
            Assert.InRange(x, -0.4 + 0.05 - 1e-3, 0.4 - 0.05 + 1e-3);
            Assert.InRange(z, -0.4 + 0.05 - 1e-3, 0.4 - 0.05 + 1e-3);
        }
    }

    [Fact]
    public void The_bodies_and_the_sand_fall_into_their_tank_without_passing_into_each_other_and_the_bodies_come_to_rest()
    {
        var path = Path.Combine(_folder, "bodies.json");
        var start = Scene.Load(path).Build();
        var (body, grain) = BodyOfEachParticle(path, start.Count);
        var run = DemoProcess.Run("scene", path, "--format", "csv", "--every", "60").Csv();
        var end = run.Rows[^1];
        var before = run.Rows[^2];
        var deepest = double.PositiveInfinity;
        double moved = 0.0, sandMoved = 0.0;
        for (var i = 0; i < start.Count; i++)
        {
            double x = end[1 + (6 * i)], y = end[2 + (6 * i)], z = end[3 + (6 * i)], r = start.GetRadius(i);
            Assert.InRange(y, r - 1e-3, 0.8);
            Assert.InRange(x, -0.6 + r - 1e-3, 0.6 - r + 1e-3);
            Assert.InRange(z, -0.6 + r - 1e-3, 0.6 - r + 1e-3);
            var step = new Vector3d(x - before[1 + (6 * i)], y - before[2 + (6 * i)], z - before[3 + (6 * i)]).Length;
            if (grain[i])
            {
                sandMoved = Math.Max(sandMoved, step);
            }
            else
            {
                moved = Math.Max(moved, step);
            }

            for (var j = 0; j < i; j++)
            {
                if (body[i] != body[j])
                {
                    var d = new Vector3d(x - end[1 + (6 * j)], y - end[2 + (6 * j)], z - end[3 + (6 * j)]).Length;
                    deepest = Math.Min(deepest, d - r - start.GetRadius(j));
                }
            }
        }

        // Two solids (two bodies, a body and a grain, two grains) touch through their particles: a few mm of overlap at
        // most under the pile's weight. The scene sleeps what stays below 5 cm/s for half a second: in the last second
        // nothing moves a millimetre (a body woken late still settles; without sleep the sand creeps a cm a second).
        var energy = end[Array.IndexOf(run.Header, "kinetic_energy")];
        _output.WriteLine($"deepest overlap of two particles of two solids {-deepest:E3} m; in the last second the farthest particle of a body moved {moved:E3} m, of the sand {sandMoved:E3} m; after 8 s, kinetic energy {energy:E3} J");
        Assert.True(deepest > -0.005, $"two particles of two solids overlap by {-deepest} m");
        Assert.True(moved < 1e-3, $"a particle of a body moved {moved} m in the last second");
        Assert.True(sandMoved < 1e-3, $"a grain moved {sandMoved} m in the last second");
        Assert.True(energy < 1e-3, $"the pile still holds {energy} J");
    }

    // The scene's solids in order: boxes of the lattice rule's counts, the boulder with what the others leave, and each
    // grain a solid of its own; and which particles are grains.
    private static (int[] Body, bool[] Grain) BodyOfEachParticle(string path, int count)
    {
        using var document = System.Text.Json.JsonDocument.Parse(File.ReadAllText(path), new System.Text.Json.JsonDocumentOptions { CommentHandling = System.Text.Json.JsonCommentHandling.Skip });
        var objects = document.RootElement.GetProperty("objects").EnumerateArray().ToArray();
        var counts = new int[objects.Length];
        for (var k = 0; k < objects.Length; k++)
        {
            if (objects[k].TryGetProperty("box", out var box))
            {
                var spacing = objects[k].GetProperty("spacing").GetDouble();
                var size = box.TryGetProperty("size", out var s)
                    ? Vector(s)
                    : Vector(box.GetProperty("max")) - Vector(box.GetProperty("min"));
                var (nx, ny, nz) = ParticlePhysics.Bodies.BodyLattice.BoxCounts(size, spacing);
                counts[k] = nx * ny * nz;
            }
        }

        var mesh = Array.FindIndex(objects, o => !o.TryGetProperty("box", out _));
        counts[mesh] = count - counts.Sum();
        var body = new int[count];
        var grain = new bool[count];
        var next = 0;
        var id = 0;
        for (var k = 0; k < objects.Length; k++)
        {
            var grains = objects[k].GetProperty("type").GetString() == "granular";
            for (var n = 0; n < counts[k]; n++)
            {
                grain[next] = grains;
                body[next++] = grains ? id++ : id;
            }

            id += grains ? 0 : 1;
        }

        return (body, grain);

        static Vector3d Vector(System.Text.Json.JsonElement e)
        {
            var v = e.EnumerateArray().Select(x => x.GetDouble()).ToArray();
            return new Vector3d(v[0], v[1], v[2]);
        }
    }

    [Fact]
    public void The_cloth_drapes_outside_the_boulder_mesh_and_the_balls_slide_down_the_terrain()
    {
        // The boulder is the OBJ's 320 facets around (0, 0.3, 0): no cloth particle (radius 0.01) nearer its centre than
        // the nearest facet plane plus its radius, less 1 mm; the balls start at x = 1.3 on the terrain's top.
        var path = Path.Combine(_folder, "drape-and-slope.json");
        var boulder = ParticlePhysics.Scenes.Meshes.ObjReader.Read(Path.Combine(_folder, "boulder.obj"));
        var inradius = double.PositiveInfinity;
        for (var t = 0; t < boulder.TriangleCount; t++)
        {
            var a = boulder.Vertex(boulder.Triangles[3 * t]);
            var n = Vector3d.Cross(boulder.Vertex(boulder.Triangles[(3 * t) + 1]) - a, boulder.Vertex(boulder.Triangles[(3 * t) + 2]) - a);
            inradius = Math.Min(inradius, Vector3d.Dot(a, n / n.Length));
        }

        var run = DemoProcess.Run("scene", path, "--duration", "2", "--format", "csv").Csv();
        var end = run.Rows[^1];
        const int cloth = 17 * 17;
        var lowest = double.PositiveInfinity;
        for (var i = 0; i < cloth; i++)
        {
            var p = new Vector3d(end[1 + (6 * i)], end[2 + (6 * i)] - 0.3, end[3 + (6 * i)]);
            Assert.True(p.Length >= inradius + 0.01 - 1e-3, $"cloth particle {i} at {p.Length} m from the boulder's centre");
            lowest = Math.Min(lowest, end[2 + (6 * i)]);
        }

        Assert.True(lowest < 0.3, $"the cloth does not hang around the boulder: lowest {lowest}");
        for (var i = cloth; i < cloth + 6; i++)
        {
            Assert.True(end[1 + (6 * i)] > 2.5, $"ball {i - cloth} stopped at x = {end[1 + (6 * i)]}");
        }
    }

    [Fact]
    public void A_scene_prints_the_contracts_columns_and_json()
    {
        var path = Path.Combine(_folder, "first-scene.json");
        var csv = DemoProcess.Run("scene", path, "--duration", "0.1", "--format", "csv");
        var header = csv.OutputLines[0].Split(',');
        Assert.Equal("t", header[0]);
        Assert.Equal(new[] { "x0", "y0", "z0", "vx0", "vy0", "vz0" }, header.Skip(1).Take(6));
        Assert.Equal(new[] { "particles", "kinetic_energy", "min_y", "max_speed" }, header.Skip(1 + (6 * 4)));

        var json = DemoProcess.Run("scene", path, "--duration", "0.1", "--format", "json");
        using var document = System.Text.Json.JsonDocument.Parse(json.Output);
        var root = document.RootElement;
        Assert.Equal(path, root.GetProperty("scene").GetString());
        Assert.Equal("xpbd", root.GetProperty("integrator").GetString());
        var final = root.GetProperty("summary").GetProperty("final");
        Assert.Equal(4, final.GetProperty("positions").GetArrayLength());
        Assert.Equal(4, final.GetProperty("velocities").GetArrayLength());
        Assert.Equal(3.0, final.GetProperty("masses")[3].GetDouble());
        Assert.Equal("Null", JsonValueKind(root.GetProperty("diverged")));
    }

    [Fact]
    public void Options_on_the_command_line_override_the_file()
    {
        var path = Path.Combine(_folder, "first-scene.json");
        var result = DemoProcess.Run("scene", path, "--integrator", "rk4", "--dt", "0.01", "--duration", "0.05");
        Assert.Equal(0, result.ExitCode);
        Assert.StartsWith($"{path}: rk4, dt = 0.01 s, 5 steps to t = 0.05 s", result.OutputLines[0], StringComparison.Ordinal);
    }

    [Fact]
    public void The_readme_shows_a_sample_scene_in_ten_lines()
    {
        var readme = File.ReadAllText(Path.Combine(ReadmeExamplesTests.RepositoryRoot(), "README.md")).Replace("\r\n", "\n");
        var sample = File.ReadAllText(Path.Combine(_folder, "first-scene.json")).Replace("\r\n", "\n");
        Assert.Contains("```json\n" + sample + "```", readme, StringComparison.Ordinal);
        Assert.True(sample.TrimEnd().Split('\n').Length <= 10, "the README's scene is more than ten lines");
    }

    [Fact]
    public void The_scenes_page_shows_what_the_program_does()
    {
        var root = ReadmeExamplesTests.RepositoryRoot();
        var page = File.ReadAllText(Path.Combine(root, "docs", "scenes.md")).Replace("\r\n", "\n");
        var sample = File.ReadAllText(Path.Combine(_folder, "first-scene.json")).Replace("\r\n", "\n");
        Assert.Contains("```json\n" + sample + "```", page, StringComparison.Ordinal);

        // The --validate example, as printed (the page names the file from the repository's root).
        var result = DemoProcess.Run("scene", "--validate", Path.Combine(_folder, "first-scene.json"));
        var printed = string.Join("\n", result.OutputLines.Select(l => "    " + l.Replace(root + Path.DirectorySeparatorChar, string.Empty, StringComparison.Ordinal)));
        Assert.Contains("scene --validate samples/scenes/first-scene.json\n" + printed + "\n", page, StringComparison.Ordinal);

        // The C# example, run here as the page writes it.
        Assert.Contains(CSharpExample, page, StringComparison.Ordinal);
        var scene = Scene.Load(Path.Combine(_folder, "newtons-cradle.json"));
        var world = scene.Build();
        var integrator = ParticlePhysics.Integrators.IntegratorCatalog.Create(scene.Settings.Integrator, scene.Settings.Tolerance, scene.Settings.Substeps);
        for (var step = 0; step < 600; step++)
        {
            world.Step(integrator, scene.Settings.TimeStep);
        }

        Assert.Equal(0.6, world.Time, 9);
        Assert.True(world.GetVelocity(4).X > 1.5, "ball 4 swings out after the impacts at t = 0.52 s");
    }

    private const string CSharpExample = """
        var scene = Scene.Load("samples/scenes/newtons-cradle.json");   // throws SceneException, one line, for a bad file
        var world = scene.Build();                                      // a new world each call
        var integrator = IntegratorCatalog.Create(scene.Settings.Integrator, scene.Settings.Tolerance, scene.Settings.Substeps);
        for (var step = 0; step < 600; step++)
        {
            world.Step(integrator, scene.Settings.TimeStep);
        }
        """;

    private static string JsonValueKind(System.Text.Json.JsonElement e) => e.ValueKind.ToString();
}
