using System;
using System.IO;
using System.Runtime.CompilerServices;
using System.Text.RegularExpressions;
using ParticlePhysics.Cloth;
using ParticlePhysics.Constraints;
using ParticlePhysics.Contacts;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Tests.Engine;

/// <summary>
/// The README's C# snippets (and the NuGet package README's) are this file's code: each test runs the code, and a last
/// test checks that every snippet in the READMEs is, line for line, the region of this file with the same name.
/// </summary>
public partial class ReadmeExamplesTests
{
    [Fact]
    public void Quickstart_runs_and_the_pendulum_hangs_below_its_pin()
    {
        // snippet: quickstart
        var system = new ParticleWorld();
        int pin = system.AddParticle(new Vector3d(0, 0, 0), mass: 1.0);
        int bob = system.AddParticle(new Vector3d(1, 0, 0), mass: 0.5);
        system.Pin(pin);

        var springs = new SpringNetwork(system);
        springs.Add(pin, bob, stiffness: 40, restLength: 1, damping: 0.5);
        system.AddForce(springs);
        system.AddForce(new Gravity());        // m (0, -9.81, 0) on every particle
        system.AddForce(new LinearDrag(1.0));  // -lambda v: damps the swing as e^(-t)

        var rk4 = new RungeKutta4();
        for (int step = 0; step < 6000; step++)
        {
            system.Step(rk4, 0.005);           // 30 s of simulated time
        }

        Console.WriteLine(system.GetPosition(bob)); // (~0, -1.1226, 0): hanging, spring stretched by m g / k
        // end snippet

        var hanging = system.GetPosition(bob);
        Assert.Equal(0, hanging.X, 3);
        Assert.Equal(-(1 + (0.5 * 9.81 / 40)), hanging.Y, 3);
    }

    [Fact]
    public void The_rod_pendulum_comes_back_after_one_period()
    {
        // snippet: rods
        var world = new ParticleWorld();
        int bob = world.AddParticle(new Vector3d(1, 0, 0), mass: 1.0);
        var rods = new RodNetwork(world);
        rods.AddAnchoredRod(bob, anchor: Vector3d.Zero, length: 1.0); // a hard constraint, not a stiff spring
        world.AddConstraints(rods);
        world.AddForce(new Gravity());

        var rk4 = new RungeKutta4();
        for (int step = 0; step < 2000; step++)
        {
            world.Step(rk4, 2.367842 / 2000); // one period: 4 K(k) / sqrt(g / L) at 90 degrees
        }

        Console.WriteLine(world.GetPosition(bob)); // (1, ~0, 0): back where it started, the rod still 1 m long
        // end snippet

        Assert.Equal(1, world.GetPosition(bob).X, 1e-9);
        Assert.Equal(0, world.GetPosition(bob).Y, 1e-5);
        Assert.Equal(1, world.GetPosition(bob).Length, 1e-12);
    }

    [Fact]
    public void The_xpbd_cloth_follows_the_hand_at_60_hz_and_flies_on_when_let_go()
    {
        // snippet: xpbd
        var cloth = new ClothBuilder { Rows = 20, Columns = 20, Spacing = 0.05, Pinning = ClothPinning.None }
            .WithSprings(stiffness: 1e6, damping: 1)  // far too stiff for rk4 at 60 Hz
            .Build();
        var hand = new KinematicBody(cloth.System, Vector3d.Zero, Rotation3d.Identity);
        hand.Attach(cloth.ParticleIndex(0, 0));      // pinned to the hand, moving with it
        hand.Attach(cloth.ParticleIndex(0, 19));

        var xpbd = new Xpbd { Substeps = 10 };       // springs projected with compliance 1 / k
        const double frame = 1.0 / 60;
        for (int f = 1; f <= 120; f++)
        {
            hand.MoveTo(new Vector3d(0.5 * f * frame, 0, 0), Rotation3d.Identity, frame); // 0.5 m/s along x
            cloth.System.Step(xpbd, frame);
        }

        hand.Detach(cloth.ParticleIndex(0, 0));      // let go: it keeps the hand's 0.5 m/s
        // end snippet

        Assert.Equal(0.5, cloth.System.GetVelocity(cloth.ParticleIndex(0, 0)).X, 1e-9);
        Assert.Equal(1.0, cloth.System.GetPosition(cloth.ParticleIndex(0, 19)).X - 0.95, 1e-9);
        Assert.All(cloth.System.Positions.ToArray(), p => Assert.True(Math.Abs(p) < 3));
    }

    [Fact]
    public void Wind_force_from_the_readme_pushes_particles_downwind()
    {
        var system = new ParticleWorld();
        system.AddParticle(Vector3d.Zero, 1.0);
        system.AddForce(new Wind { AirVelocity = new Vector3d(5, 0, 0) });
        system.Step(new RungeKutta4(), 0.1);
        Assert.True(system.GetVelocity(0).X > 0);
        Assert.Equal(0, system.GetVelocity(0).Y);
    }

    [Fact]
    public void Contacts_snippet_bounces_the_ball_at_the_exact_time()
    {
        var saved = Console.Out;
        using var printed = new StringWriter(System.Globalization.CultureInfo.InvariantCulture);
        Console.SetOut(printed);

        // snippet: contacts
        var world = new ParticleWorld();
        int ball = world.AddParticle(new Vector3d(0, 1, 0), mass: 1.0);
        world.SetRadius(ball, 0.1);
        world.AddForce(new Gravity());

        var contacts = new ContactSet();                  // a stage after the integrator's step
        contacts.Add(PlaneObstacle.Ground(restitution: 0.8, friction: 0.3));
        contacts.Add(new SphereObstacle(new Vector3d(2, 0.5, 0), radius: 0.5));
        world.AddConstraints(contacts);

        var rk4 = new RungeKutta4();
        for (int step = 0; step < 1000; step++)
        {
            world.Step(rk4, 0.001);
            foreach (ContactImpact impact in contacts.Impacts)  // resolved at their time within the step
            {
                Console.WriteLine(FormattableString.Invariant($"impact at t = {impact.Time:F6} s, {impact.NormalSpeed:F4} m/s"));
            }
        }
        // impact at t = 0.428353 s, 4.2021 m/s: t1 = sqrt(2 (h - r) / g), u1 = g t1
        // end snippet

        Console.SetOut(saved);
        var line = Assert.Single(printed.ToString().Split('\n', StringSplitOptions.RemoveEmptyEntries));
        Assert.Equal(FormattableString.Invariant($"impact at t = {Math.Sqrt(2 * 0.9 / 9.81):F6} s, {Math.Sqrt(2 * 9.81 * 0.9):F4} m/s"), line.TrimEnd());
    }

    [Theory]
    [InlineData("README.md", 5)]
    [InlineData("src/ParticlePhysics/README.md", 1)]   // the NuGet package's README
    public void Every_readme_snippet_is_the_code_the_tests_run(string readmePath, int snippets)
    {
        var readme = File.ReadAllText(Path.Combine(RepositoryRoot(), readmePath));
        var source = File.ReadAllText(ThisFile());
        var blocks = ReadmeSnippet().Matches(readme);
        Assert.Equal(snippets, blocks.Count);
        foreach (Match block in blocks)
        {
            var name = block.Groups["name"].Value;
            var region = Regex.Match(source, $@"// snippet: {name}\r?\n(?<code>.*?)\r?\n[ \t]*// end snippet", RegexOptions.Singleline);
            Assert.True(region.Success, $"no region '{name}' in {ThisFile()}");
            Assert.Equal(Dedent(region.Groups["code"].Value), Dedent(block.Groups["code"].Value));
        }
    }

    internal static string RepositoryRoot()
    {
        var directory = Path.GetDirectoryName(ThisFile());
        while (directory is not null && !File.Exists(Path.Combine(directory, "ParticlePhysics.sln")))
        {
            directory = Path.GetDirectoryName(directory);
        }

        return directory ?? throw new InvalidOperationException("ParticlePhysics.sln not found above " + ThisFile());
    }

    private static string ThisFile([CallerFilePath] string path = "") => path;

    private static string Dedent(string code)
    {
        var lines = code.Replace("\r\n", "\n", StringComparison.Ordinal).Split('\n');
        var indent = int.MaxValue;
        foreach (var line in lines)
        {
            if (line.Trim().Length > 0)
            {
                indent = Math.Min(indent, line.Length - line.TrimStart().Length);
            }
        }

        for (var i = 0; i < lines.Length; i++)
        {
            lines[i] = lines[i].Length >= indent ? lines[i][indent..].TrimEnd() : lines[i].Trim();
        }

        return string.Join("\n", lines).Trim();
    }

    [GeneratedRegex(@"<!-- snippet: (?<name>[a-z-]+) -->\s*```csharp\r?\n(?<code>.*?)```", RegexOptions.Singleline)]
    private static partial Regex ReadmeSnippet();

    // snippet: wind
    /// <summary>A uniform wind: drag toward the air's velocity, F = c (w - v).</summary>
    public sealed class Wind : IForceGenerator
    {
        public Vector3d AirVelocity { get; set; }

        public double Coefficient { get; set; } = 0.02;

        public void AddForces(in ParticleState state, Span<double> forces)
        {
            for (int i = 0; i < state.Count; i++)
            {
                var f = Coefficient * (AirVelocity - state.Velocity(i));
                forces[3 * i] += f.X;
                forces[(3 * i) + 1] += f.Y;
                forces[(3 * i) + 2] += f.Z;
            }
        }
    }

    // end snippet
}
