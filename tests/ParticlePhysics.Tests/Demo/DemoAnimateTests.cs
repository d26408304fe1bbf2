using System;
using System.Globalization;
using System.IO;
using System.Linq;
using System.Text.Json;
using System.Text.RegularExpressions;
using ParticlePhysics.Demo.Animation;
using ParticlePhysics.Demo.Running;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Engine;

namespace ParticlePhysics.Tests.Demo;

/// <summary>
/// <c>--animate FILE.html</c> writes one page that holds everything it shows: the frames decode to the run's own
/// positions (in single precision), at the display rate, with the scene's pins, springs, rods, anchors, radii,
/// colliders and surface; it
/// names nothing on the network. That the page plays in a browser is checked by tests/browser (headless Chromium).
/// </summary>
public sealed partial class DemoAnimateTests : IDisposable
{
    private readonly string _folder = Directory.CreateTempSubdirectory("pp-demo-animate-").FullName;

    public void Dispose() => Directory.Delete(_folder, recursive: true);

    [Fact]
    public void The_frames_are_the_runs_positions_at_the_display_rate()
    {
        var path = Path.Combine(_folder, "cloth.html");

        var result = DemoProcess.Run("cloth", "--duration", "0.1", "--every", "1", "--format", "csv", "--animate", path);

        Assert.Equal(0, result.ExitCode);
        var (header, rows) = result.Csv();
        var page = Page.Read(path);
        var n = page.Data.GetProperty("particles").GetInt32();
        Assert.Equal(121, n);
        var times = page.Data.GetProperty("times").EnumerateArray().Select(t => t.GetDouble()).ToArray();

        // 0.1 s at 60 frames per second: t = 0, 1/60, ..., 6/60, each at the step nearest to it (dt = 1 ms).
        Assert.Equal(new[] { 0, 0.017, 0.033, 0.05, 0.067, 0.083, 0.1 }, times);
        var frames = ReplayPage.DecodeFrames(page.Frames, 3 * n);
        Assert.Equal(times.Length * 3 * n, frames.Length);
        for (var f = 0; f < times.Length; f++)
        {
            var row = rows.Single(r => r[0] == times[f]);
            for (var i = 0; i < n; i++)
            {
                for (var c = 0; c < 3; c++)
                {
                    Assert.Equal((float)row[Array.IndexOf(header, "xyz"[c] + i.ToString(CultureInfo.InvariantCulture))], frames[(((f * n) + i) * 3) + c]);
                }
            }
        }
    }

    [Fact]
    public void The_cloth_page_holds_its_pins_springs_and_surface()
    {
        var path = Path.Combine(_folder, "cloth.html");

        var result = DemoProcess.Run("cloth", "--duration", "0.05", "--format", "csv", "--animate", path);

        Assert.Equal(0, result.ExitCode);
        var data = Page.Read(path).Data;
        Assert.Equal(new[] { 0, 10 }, data.GetProperty("pinned").EnumerateArray().Select(e => e.GetInt32()));
        var world = new ClothScenario().Build();
        var springs = (Forces.SpringNetwork)world.Forces.Single(f => f is Forces.SpringNetwork);
        var ends = data.GetProperty("links").GetProperty("spring").EnumerateArray().Select(e => e.GetInt32()).ToArray();
        Assert.Equal(2 * springs.Count, ends.Length);
        Assert.Equal(springs.GetEnds(springs.Count - 1), (ends[^2], ends[^1]));
        Assert.Equal(3 * 2 * 10 * 10, data.GetProperty("triangles").GetArrayLength());
        Assert.Equal(0, data.GetProperty("anchors").GetArrayLength());
        Assert.Equal("completed", data.GetProperty("status").GetString());
        Assert.Contains("final state at t = 0.05 s: min_y = ", data.GetProperty("summary").GetString(), StringComparison.Ordinal);
        Assert.Equal(new[] { "min_y", "max_speed", "energy" }, data.GetProperty("valueNames").EnumerateArray().Select(e => e.GetString()));
    }

    [Fact]
    public void A_spring_to_a_fixed_anchor_ends_at_the_anchor()
    {
        var path = Path.Combine(_folder, "msd.html");

        var result = DemoProcess.Run("mass-spring-damper", "--duration", "1", "--format", "csv", "--animate", path);

        Assert.Equal(0, result.ExitCode);
        var data = Page.Read(path).Data;
        Assert.Equal(new[] { 0.0, 0, 0 }, data.GetProperty("anchors")[0].EnumerateArray().Select(e => e.GetDouble()));
        Assert.Equal(new[] { 0, 1 }, data.GetProperty("links").GetProperty("spring").EnumerateArray().Select(e => e.GetInt32())); // particle 0 to node N + 0
    }

    [Fact]
    public void Rods_and_cables_are_links_of_their_own_kind_with_their_lengths()
    {
        var pendulum = Path.Combine(_folder, "pendulum.html");
        var chain = Path.Combine(_folder, "chain.html");

        Assert.Equal(0, DemoProcess.Run("pendulum", "--duration", "0.5", "--format", "csv", "--animate", pendulum).ExitCode);
        Assert.Equal(0, DemoProcess.Run("hanging-chain", "--duration", "0.5", "--format", "csv", "--animate", chain).ExitCode);

        var rod = Page.Read(pendulum).Data;
        Assert.Equal(new[] { 0.0, 0, 0 }, rod.GetProperty("anchors")[0].EnumerateArray().Select(e => e.GetDouble()));
        Assert.Equal(new[] { 0, 1 }, rod.GetProperty("links").GetProperty("rod").EnumerateArray().Select(e => e.GetInt32())); // the bob to the anchor
        Assert.False(rod.GetProperty("links").TryGetProperty("spring", out _));
        var links = Page.Read(chain).Data;
        Assert.Equal(Enumerable.Range(0, 10).SelectMany(i => new[] { i, i + 1 }), links.GetProperty("links").GetProperty("rod").EnumerateArray().Select(e => e.GetInt32()));
        Assert.Equal(new[] { 0, 10 }, links.GetProperty("pinned").EnumerateArray().Select(e => e.GetInt32()));
    }

    [Fact]
    public void Contact_scenarios_carry_their_colliders_and_radii()
    {
        var drape = Path.Combine(_folder, "drape.html");
        var ball = Path.Combine(_folder, "ball.html");
        var collision = Path.Combine(_folder, "collision.html");

        Assert.Equal(0, DemoProcess.Run("drape", "--duration", "0.05", "--format", "csv", "--animate", drape).ExitCode);
        Assert.Equal(0, DemoProcess.Run("bouncing-ball", "--radius", "0.1", "--duration", "0.5", "--format", "csv", "--animate", ball).ExitCode);
        Assert.Equal(0, DemoProcess.Run("collision", "--radius", "0.2", "--duration", "0.5", "--format", "csv", "--animate", collision).ExitCode);

        // The drape: a sphere of radius 0.3 at (S/2, -0.5, S/2), every particle of radius 0.01, the cloth's surface.
        var data = Page.Read(drape).Data;
        var sphere = Assert.Single(data.GetProperty("colliders").EnumerateArray());
        Assert.Equal("sphere", sphere.GetProperty("kind").GetString());
        Assert.Equal(0.3, sphere.GetProperty("radius").GetDouble());
        Assert.Equal(new[] { 0.5, -0.5, 0.5 }, sphere.GetProperty("center").EnumerateArray().Select(e => e.GetDouble()));
        Assert.False(sphere.TryGetProperty("velocity", out _)); // it stands still
        Assert.All(data.GetProperty("radii").EnumerateArray(), r => Assert.Equal(0.01, r.GetDouble()));
        Assert.Equal(121, data.GetProperty("radii").GetArrayLength());
        Assert.Equal(3 * 2 * 10 * 10, data.GetProperty("triangles").GetArrayLength());
        Assert.Empty(data.GetProperty("pinned").EnumerateArray());

        // The ball: the ground plane y = 0 (its normal is the second axis) and the ball's radius.
        data = Page.Read(ball).Data;
        var ground = Assert.Single(data.GetProperty("colliders").EnumerateArray());
        Assert.Equal("plane", ground.GetProperty("kind").GetString());
        Assert.Equal(new[] { 0.0, 0, 0 }, ground.GetProperty("center").EnumerateArray().Select(e => e.GetDouble()));
        Assert.Equal(new[] { 0.0, 1, 0 }, ground.GetProperty("axes")[1].EnumerateArray().Select(e => e.GetDouble()));
        Assert.Equal(new[] { 0.1 }, data.GetProperty("radii").EnumerateArray().Select(e => e.GetDouble()));

        // The collision: no collider, two particles of the given radius.
        data = Page.Read(collision).Data;
        Assert.Equal(0, data.GetProperty("colliders").GetArrayLength());
        Assert.Equal(new[] { 0.2, 0.2 }, data.GetProperty("radii").EnumerateArray().Select(e => e.GetDouble()));
    }

    [Fact]
    public void The_page_loads_nothing_from_the_network()
    {
        var path = Path.Combine(_folder, "chain.html");

        Assert.Equal(0, DemoProcess.Run("two-mass-chain", "--format", "csv", "--animate", path).ExitCode);

        var html = File.ReadAllText(path);
        Assert.DoesNotMatch(NetworkReference(), html);
        Assert.Equal(3, Regex.Matches(html, "<script").Count); // the data, the frames and the inline renderer
        Assert.Contains("<title>two-mass-chain: rk4, dt = 0.01 s, 2000 steps to t = 20 s</title>", html, StringComparison.Ordinal);
    }

    [Fact]
    public void A_diverged_run_still_writes_its_page_up_to_the_last_good_state()
    {
        var path = Path.Combine(_folder, "diverged.html");

        var result = DemoProcess.Run("cloth", "--dt", "0.0166667", "--format", "csv", "--animate", path);

        Assert.Equal(3, result.ExitCode);
        var page = Page.Read(path);
        Assert.Equal("diverged", page.Data.GetProperty("status").GetString());
        var times = page.Data.GetProperty("times").EnumerateArray().Select(t => t.GetDouble()).ToArray();
        Assert.Equal(17 * 0.0166667, times[^1]); // the last good step, whose time the error line gives as 0.283334
        Assert.All(ReplayPage.DecodeFrames(page.Frames, 3 * 121), v => Assert.True(float.IsFinite(v)));
    }

    [Fact]
    public void A_plain_ode_has_nothing_to_animate()
    {
        var path = Path.Combine(_folder, "ode.html");

        var result = DemoProcess.Run("scalar-ode", "--animate", path);

        Assert.Equal(2, result.ExitCode);
        Assert.Equal("error: --animate replays particles, and scalar-ode is a plain ODE with none; use --plot FILE.svg for its curve.", result.ErrorLines.Single());
        Assert.False(File.Exists(path));
    }

    [Fact]
    public void A_page_that_cannot_be_written_is_refused_before_the_run()
    {
        var path = Path.Combine(_folder, "missing", "cloth.html");

        var result = DemoProcess.Run("cloth", "--animate", path);

        Assert.Equal(2, result.ExitCode);
        Assert.Equal(string.Empty, result.Output);
        Assert.StartsWith("error: --animate cannot write '", result.ErrorLines.Single(), StringComparison.Ordinal);
        Assert.Contains("does not exist", result.Error, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData(11, 5.0)]
    [InlineData(64, 5.0)]
    [InlineData(256, 5.0)]
    public void A_recording_keeps_to_the_display_rate_and_its_size_budget(int side, double duration)
    {
        var setup = new ClothSetup("cloth", () => throw new InvalidOperationException("not run"), side) { TableColumnList = new[] { "t", "min_y" } };
        var plan = new RunPlan("rk4", 0.001, RunPlan.StepsFor(duration, 0.001), 1, 1e-8);
        var recorder = new ReplayRecorder(setup, setup.ParticleCount, plan);

        var frames = Enumerable.Range(0, plan.Steps + 1).Count(recorder.Wants);

        Assert.True(frames <= (duration * ReplayRecorder.FramesPerSecond) + 1, $"{frames} frames");
        Assert.True(frames * 12L * side * side <= ReplayRecorder.MaxFrameBytes + (12L * side * side), $"{frames} frames of {side} x {side}");
        Assert.True(frames >= Math.Min((duration * ReplayRecorder.FramesPerSecond) + 1, ReplayRecorder.MaxFrameBytes / (12.0 * side * side)) - 1, $"{frames} frames");
        Assert.True(recorder.Wants(plan.Steps) || frames > 0);
    }

    [Fact]
    public void The_frame_coding_is_lossless_for_every_float()
    {
        var values = new[] { 0f, -0f, 1.5f, -2.25e-30f, float.MaxValue, float.Epsilon, 3.1e11f, -7f, 0.1f, 0.2f, 0.30000001f, 1e-7f };

        var decoded = ReplayPage.DecodeFrames(ReplayPage.EncodeFrames(values, 3), 3);

        Assert.Equal(values.Select(BitConverter.SingleToInt32Bits), decoded.Select(BitConverter.SingleToInt32Bits));
    }

    [Fact]
    public void A_profiled_run_keeps_each_stages_time_per_step_at_every_frame_and_an_unprofiled_one_none()
    {
        var path = Path.Combine(_folder, "profiled.html");
        var plainPath = Path.Combine(_folder, "plain.html");

        var result = DemoProcess.Run("cloth", "--duration", "0.1", "--format", "csv", "--profile", "--animate", path);
        Assert.Equal(0, DemoProcess.Run("cloth", "--duration", "0.1", "--format", "csv", "--animate", plainPath).ExitCode);

        Assert.Equal(0, result.ExitCode);
        var data = Page.Read(path).Data;
        var profile = data.GetProperty("profile");
        Assert.Equal(ReplayRecorder.StageNames, profile.GetProperty("stages").EnumerateArray().Select(e => e.GetString()));
        var seconds = profile.GetProperty("seconds").EnumerateArray().Select(e => e.GetDouble()).ToArray();
        var frames = data.GetProperty("times").GetArrayLength();
        Assert.Equal(4 * frames, seconds.Length);
        Assert.All(seconds, s => Assert.True(s >= 0.0));
        Assert.Equal(0.0, seconds.Take(4).Sum()); // no step before the first frame
        for (var f = 1; f < frames; f++)
        {
            Assert.True(seconds.Skip(4 * f).Take(4).Sum() > 0.0, $"frame {f}'s steps were timed");
        }

        Assert.False(Page.Read(plainPath).Data.TryGetProperty("profile", out _));
    }

    [Fact]
    public void The_page_template_is_the_html_file_in_the_demo()
    {
        var file = Path.Combine(ReadmeExamplesTests.RepositoryRoot(), "samples", "ParticlePhysics.Demo", "Animation", "replay.html");

        Assert.Equal(File.ReadAllText(file).ReplaceLineEndings(), ReplayPage.Template().ReplaceLineEndings());
    }

    [GeneratedRegex(@"(?i)\b(?:https?:|wss?:|ftp:)//|<(?:script|img|iframe|link)[^>]*\s(?:src|href)\s*=|@import|url\(\s*['""]?(?!data:|#)")]
    private static partial Regex NetworkReference();

    private sealed record Page(JsonElement Data, byte[] Frames)
    {
        public static Page Read(string path)
        {
            var html = File.ReadAllText(path);
            var data = Between(html, "<script type=\"application/json\" id=\"replay-data\">", "</script>");
            var frames = Between(html, "<script type=\"text/plain\" id=\"replay-frames\">", "</script>");
            return new Page(JsonDocument.Parse(data).RootElement.Clone(), Convert.FromBase64String(frames.Trim()));
        }

        private static string Between(string text, string start, string end)
        {
            var from = text.IndexOf(start, StringComparison.Ordinal) + start.Length;
            return text[from..text.IndexOf(end, from, StringComparison.Ordinal)];
        }
    }
}
