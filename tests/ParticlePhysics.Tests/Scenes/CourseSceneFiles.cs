using System;
using System.Collections.Generic;
using System.Globalization;
using System.Linq;
using System.Text;
using ParticlePhysics.Cloth;
using ParticlePhysics.Constraints;
using ParticlePhysics.Contacts;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Tests.Scenes;

/// <summary>
/// Writes the course's scenarios as scene files (samples/scenes/), each the scenario's world with its defaults:
/// positions, masses and rest lengths are taken from the world the scenario builds, to the last bit, so that the scene
/// gives the scenario command's rows bit for bit. A fixed anchor becomes a pinned particle listed after the
/// scenario's own (so particle i is the scenario's particle i). <see cref="SceneSamplesTests"/> holds the committed
/// files to what this writes (PP_WRITE_SCENES=1 rewrites them).
/// </summary>
internal static class CourseSceneFiles
{
    public static IReadOnlyList<(string Name, string Text)> All() => new[]
    {
        ("free-fall", FreeFall()),
        ("mass-spring-damper", MassSpringDamper()),
        ("two-mass-chain", TwoMassChain()),
        ("cloth", Cloth(new ClothScenario().Build(), "cloth", null)),
        ("pendulum", Pendulum()),
        ("hanging-chain", HangingChain()),
        ("bouncing-ball", BouncingBall()),
        ("collision", Collision()),
        ("drape", Drape()),
    };

    private static string FreeFall()
    {
        var world = new FreeFallScenario().Build();
        return Scene(
            "The course's free fall with viscous friction (free-fall): 10 g at 300 m, drag 0.01 N s/m.",
            "dotnet run --project samples/ParticlePhysics.Demo -- free-fall gives the same rows.",
            "rk4", 0.01, 10, drag: 0.01, gravity: null,
            Particles(world, Enumerable.Range(0, 1), pinned: Array.Empty<int>()));
    }

    private static string MassSpringDamper()
    {
        var world = new MassSpringDamperScenario().Build();
        return Scene(
            "One mass on a zero-rest-length spring to a fixed anchor at the origin (mass-spring-damper): F = -k x, drag 0.1.",
            "The anchor is particle 1, pinned; restLength 0 is the course's linear spring -k (x0 - x1).",
            "rk4", 0.01, 20, drag: 0.1, gravity: null,
            Particles(world, Enumerable.Range(0, 1), pinned: Array.Empty<int>()) + ",\n" + Anchor(Vector3d.Zero) + ",\n"
            + "    { \"type\": \"springs\", \"pairs\": [[0, 1]], \"stiffness\": 1, \"restLength\": 0 }");
    }

    private static string TwoMassChain()
    {
        var world = new TwoMassChainScenario().Build();
        return Scene(
            "Anchor - spring 1 - mass 0 - spring 2 - mass 1 (two-mass-chain): k = 10 N/m, rest lengths 1 and 0, drag 0.5.",
            "The anchor is particle 2, pinned; restLength 0 on spring 2 is the course's linear spring -k (x0 - x1).",
            "rk4", 0.01, 20, drag: 0.5, gravity: null,
            Particles(world, Enumerable.Range(0, 2), pinned: Array.Empty<int>()) + ",\n" + Anchor(Vector3d.Zero) + ",\n"
            + "    { \"type\": \"springs\", \"pairs\": [[0, 1]], \"stiffness\": 10, \"restLength\": 0 },\n"
            + "    { \"type\": \"springs\", \"pairs\": [[0, 2]], \"stiffness\": 10, \"restLength\": 1 }");
    }

    private static string Pendulum()
    {
        var world = new PendulumScenario().Build();
        return Scene(
            "A 1 kg bob on a 1 m rod to an anchor at the origin, released at rest at 90 degrees (pendulum).",
            "The anchor is particle 1, pinned; the bob starts at (L sin 90, -L cos 90, 0) to the last bit.",
            "rk4", 0.001, 10, drag: 0, gravity: null,
            Particles(world, Enumerable.Range(0, 1), pinned: Array.Empty<int>()) + ",\n" + Anchor(Vector3d.Zero) + ",\n"
            + "    { \"type\": \"rods\", \"pairs\": [[0, 1]], \"length\": 1 }");
    }

    private static string HangingChain()
    {
        var scenario = new HangingChainScenario();
        var world = scenario.Build();
        var n = world.Count;
        var pairs = string.Join(", ", Enumerable.Range(0, n - 1).Select(i => Invariant($"[{i}, {i + 1}]")));
        return Scene(
            "11 particles joined by 10 rods of 0.2 m between two pins 1.5 m apart, starting in a V (hanging-chain).",
            "It settles into the discrete catenary.",
            "rk4", 0.001, 20, drag: 0.1, gravity: null,
            Particles(world, Enumerable.Range(0, n), pinned: new[] { 0, n - 1 }) + ",\n"
            + $"    {{ \"type\": \"rods\", \"pairs\": [{pairs}], \"length\": {R(scenario.RodLength)} }}");
    }

    private static string BouncingBall()
    {
        var world = new BouncingBallScenario().Build();
        return Scene(
            "A 1 kg ball dropped from 1 m onto the ground (bouncing-ball), restitution 0.8.",
            "It rests from t = 4.06 s on.",
            "rk4", 0.001, 5, drag: 0, gravity: null,
            Particles(world, Enumerable.Range(0, 1), pinned: Array.Empty<int>()),
            "    { \"type\": \"plane\", \"point\": [0, 0, 0], \"normal\": [0, 1, 0], \"restitution\": 0.8 }");
    }

    private static string Collision()
    {
        var world = new CollisionScenario().Build();
        return Scene(
            "Two 1 kg particles of radius 0.1 m meet head-on at 1 m/s each (collision), restitution 1, no gravity.",
            "They touch at t = 0.9 s and leave with their velocities exchanged.",
            "rk4", 0.001, 2, drag: 0, gravity: Vector3d.Zero,
            Particles(world, Enumerable.Range(0, 2), pinned: Array.Empty<int>()),
            colliders: null,
            particleCollisions: "{ \"restitution\": 1 }");
    }

    private static string Drape()
    {
        var scenario = new DrapeScenario();
        var world = scenario.Build();
        var c = scenario.SphereCenter;
        return Cloth(
            world,
            "drape",
            $"    {{ \"type\": \"sphere\", \"center\": {V(c)}, \"radius\": {R(scenario.SphereRadius)}, \"friction\": {R(scenario.Friction)} }}");
    }

    // The cloth and the drape: one particles object, one springs object with the cloth's springs in the builder's
    // order (structural, shear and bend interleaved particle by particle) and their rest lengths.
    private static string Cloth(ParticleWorld world, string name, string? sphere)
    {
        var springs = (Forces.SpringNetwork)world.Forces[0];
        var pins = Enumerable.Range(0, world.Count).Where(world.IsPinned).ToArray();
        var pairs = new StringBuilder();
        var lengths = new StringBuilder();
        for (var s = 0; s < springs.Count; s++)
        {
            var (a, b) = springs.GetEnds(s);
            pairs.Append(s == 0 ? string.Empty : s % 8 == 0 ? ",\n        " : ", ").Append(Invariant($"[{a}, {b}]"));
            lengths.Append(s == 0 ? string.Empty : s % 8 == 0 ? ",\n        " : ", ").Append(R(springs.GetRestLength(s)));
        }

        var springsObject = "    {\n      \"type\": \"springs\", \"stiffness\": 50, \"damping\": 0.05,\n"
            + "      // structural (r), shear (r sqrt 2) and bend (2 r), in the order the cloth builder adds them\n"
            + $"      \"pairs\": [\n        {pairs}\n      ],\n      \"restLengths\": [\n        {lengths}\n      ]\n    }}";
        return sphere is null
            ? Scene(
                "The course's square cloth (cloth): 11 x 11 particles 0.1 m apart in y = 0, 1 kg in all, held by two corners.",
                "Springs of 50 N/m with damping 0.05 N s/m: structural, shear and bend; drag 0.01 N s/m.",
                "rk4", 0.001, 5, drag: 0.01, gravity: null,
                Particles(world, Enumerable.Range(0, world.Count), pins) + ",\n" + springsObject)
            : Scene(
                "The cloth pinned nowhere, of particles of radius 0.01 m, falls onto a sphere (drape), friction 0.5.",
                "The cloth collides with itself (pairs joined by a spring excepted).",
                "rk4", 0.001, 3, drag: 0.01, gravity: null,
                Particles(world, Enumerable.Range(0, world.Count), pins) + ",\n" + springsObject,
                sphere,
                particleCollisions: "true");
    }

    private static string Scene(
        string title, string note, string integrator, double dt, double duration, double drag, Vector3d? gravity, string objects,
        string? colliders = null, string? particleCollisions = null)
    {
        var text = new StringBuilder();
        text.Append("// ").Append(title).Append('\n');
        text.Append("// ").Append(note).Append('\n');
        text.Append("// Written by tests/ParticlePhysics.Tests/Scenes/CourseSceneFiles.cs from the scenario's own world; a test holds\n");
        text.Append("// its rows to the scenario command's, bit for bit.\n");
        text.Append("{\n");
        text.Append($"  \"integrator\": \"{integrator}\",\n");
        text.Append($"  \"dt\": {R(dt)},\n");
        text.Append($"  \"duration\": {R(duration)},\n");
        if (drag > 0)
        {
            text.Append($"  \"drag\": {R(drag)},\n");
        }

        if (gravity is { } g)
        {
            text.Append($"  \"gravity\": {V(g)},\n");
        }

        if (particleCollisions is not null)
        {
            text.Append($"  \"particleCollisions\": {particleCollisions},\n");
        }

        text.Append("  \"objects\": [\n").Append(objects).Append("\n  ]");
        if (colliders is not null)
        {
            text.Append(",\n  \"colliders\": [\n").Append(colliders).Append("\n  ]");
        }

        return text.Append("\n}\n").ToString();
    }

    private static string Particles(ParticleWorld world, IEnumerable<int> indices, int[] pinned)
    {
        var list = indices.ToArray();
        var positions = string.Join(",\n        ", list.Select(i => V(world.GetPosition(i))));
        var text = new StringBuilder("    {\n      \"type\": \"particles\",\n");
        text.Append($"      \"positions\": [\n        {positions}\n      ]");
        if (list.Any(i => world.GetVelocity(i) != Vector3d.Zero))
        {
            text.Append($",\n      \"velocities\": [{string.Join(", ", list.Select(i => V(world.GetVelocity(i))))}]");
        }

        var masses = list.Select(world.GetMass).Distinct().ToArray();
        text.Append(masses.Length == 1 ? $",\n      \"mass\": {R(masses[0])}" : $",\n      \"masses\": [{string.Join(", ", list.Select(i => R(world.GetMass(i))))}]");
        var radii = list.Select(world.GetRadius).Distinct().ToArray();
        if (radii.Length > 1 || radii[0] > 0)
        {
            text.Append(radii.Length == 1 ? $",\n      \"radius\": {R(radii[0])}" : $",\n      \"radii\": [{string.Join(", ", list.Select(i => R(world.GetRadius(i))))}]");
        }

        if (pinned.Length > 0)
        {
            text.Append($",\n      \"pinned\": [{string.Join(", ", pinned)}]");
        }

        return text.Append("\n    }").ToString();
    }

    private static string Anchor(Vector3d at) =>
        $"    {{ \"type\": \"particles\", \"positions\": [{V(at)}], \"pinned\": [0] }}";

    private static string V(Vector3d v) => $"[{R(v.X)}, {R(v.Y)}, {R(v.Z)}]";

    private static string R(double x) => x.ToString("R", CultureInfo.InvariantCulture); // -0 stays -0: the same bits

    private static string Invariant(FormattableString text) => text.ToString(CultureInfo.InvariantCulture);
}
