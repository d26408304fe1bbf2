using System;
using System.Collections.Generic;
using System.Globalization;
using System.IO;
using System.Linq;
using System.Text;
using ParticlePhysics.Aerodynamics;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenes.Json;
using ParticlePhysics.Scenes.Kinds;

namespace ParticlePhysics.Scenes;

/// <summary>
/// A whole simulation read from a scene file: its settings, its objects and its colliders, checked, ready to build a
/// <see cref="ParticleWorld"/> as often as needed. Every problem of the file is a <see cref="SceneException"/>, found
/// while loading (a particle index out of range included), before anything is built.
/// </summary>
/// <example>
/// <code>
/// var scene = Scene.Load("samples/scenes/newtons-cradle.json");
/// var world = scene.Build();
/// var integrator = IntegratorCatalog.Create(scene.Settings.Integrator, scene.Settings.Tolerance, scene.Settings.Substeps);
/// world.Step(integrator, scene.Settings.TimeStep);
/// </code>
/// </example>
public sealed class Scene
{
    private readonly List<SceneObject> _objects;
    private readonly List<SceneCollider> _colliders;

    private Scene(string file, SceneSettings settings, List<SceneObject> objects, List<SceneCollider> colliders, int particles, List<string> kinds)
    {
        File = file;
        Settings = settings;
        _objects = objects;
        _colliders = colliders;
        ParticleCount = particles;
        ObjectKinds = kinds;
    }

    /// <summary>The file, as it was named.</summary>
    public string File { get; }

    /// <summary>Gravity, drag, the integrator, the step, the duration, particle collisions.</summary>
    public SceneSettings Settings { get; }

    /// <summary>The number of particles the scene makes.</summary>
    public int ParticleCount { get; }

    /// <summary>The <c>"type"</c> of each object, in order.</summary>
    public IReadOnlyList<string> ObjectKinds { get; }

    /// <summary>The <c>"type"</c> of each collider, in order.</summary>
    public IReadOnlyList<string> ColliderKinds => _colliders.ConvertAll(c => c.Kind);

    /// <summary>Reads and checks a scene file (UTF-8 JSON with // comments and trailing commas).</summary>
    /// <param name="path">The file; paths inside it (OBJ meshes) are relative to its folder.</param>
    /// <exception cref="SceneException">The file cannot be read or used; the message says where and why.</exception>
    public static Scene Load(string path)
    {
        if (path is null)
        {
            throw new ArgumentNullException(nameof(path));
        }

        var document = JsonParser.ParseFile(path, path);
        return Read(document, Path.GetDirectoryName(Path.GetFullPath(path)) ?? ".");
    }

    /// <summary>Reads and checks a scene from its text.</summary>
    /// <param name="json">The scene.</param>
    /// <param name="file">The name messages give it.</param>
    /// <param name="directory">The folder relative paths inside it start from (default: the current folder).</param>
    /// <exception cref="SceneException">The scene cannot be used; the message says where and why.</exception>
    public static Scene Parse(string json, string file = "scene.json", string? directory = null)
    {
        if (json is null)
        {
            throw new ArgumentNullException(nameof(json));
        }

        return Read(JsonParser.ParseText(json, file), directory ?? Directory.GetCurrentDirectory());
    }

    /// <summary>Builds a new world at t = 0: particles in numbering order, then springs, links, loads, drag, gravity and contacts.</summary>
    /// <exception cref="SceneException">A length left out that the particles' start makes unusable.</exception>
    public ParticleWorld Build() => Build(out _);

    /// <summary>
    /// What the scene builds, in a few lines: particles (pinned, with a radius), springs, rods, cables and loads,
    /// colliders by kind, particle collisions, and the run (integrator, dt, duration).
    /// </summary>
    public string Describe()
    {
        var world = Build(out var counts);
        int pinned = 0, round = 0;
        for (var i = 0; i < world.Count; i++)
        {
            pinned += world.IsPinned(i) ? 1 : 0;
            round += world.GetRadius(i) > 0 ? 1 : 0;
        }

        string Count(string kind) => (counts.TryGetValue(kind, out var n) ? n : 0).ToString(CultureInfo.InvariantCulture);
        var s = Settings;
        var text = new StringBuilder();
        text.AppendLine(Invariant($"particles: {world.Count} ({pinned} pinned, {round} with a radius)"));
        text.AppendLine($"springs: {Count("springs")}, rods: {Count("rods")}, cables: {Count("cables")}, loads: {Count("loads")}");
        if (counts.ContainsKey("cloth triangles") || counts.ContainsKey("bending elements"))
        {
            text.AppendLine($"cloth triangles: {Count("cloth triangles")}, bending elements: {Count("bending elements")}");
        }

        var solids = counts.ContainsKey("rigid bodies") || counts.ContainsKey("soft bodies") || counts.ContainsKey("grains");
        if (solids)
        {
            text.AppendLine($"rigid bodies: {Count("rigid bodies")}, soft bodies: {Count("soft bodies")}, grains: {Count("grains")}");
        }

        if (counts.ContainsKey("fluid particles"))
        {
            text.AppendLine($"fluid particles: {Count("fluid particles")}");
        }

        text.AppendLine(_colliders.Count == 0
            ? "colliders: none"
            : "colliders: " + string.Join(", ", _colliders.GroupBy(c => c.Kind).Select(g => Invariant($"{g.Count()} {g.Key}"))));
        text.AppendLine(s.ParticleCollisions
            ? Invariant($"particle collisions: on (restitution {s.ParticleRestitution:R}, friction {s.ParticleFriction:R})")
            : solids
                ? "particle collisions: off (but solids collide with every particle with a radius)"
                : "particle collisions: off");
        text.AppendLine(Invariant($"gravity: [{s.Gravity.X:R}, {s.Gravity.Y:R}, {s.Gravity.Z:R}] m/s^2, drag: {s.Drag:R} N s/m"));
        if (s.SleepSpeed > 0)
        {
            text.AppendLine(Invariant($"sleep: below {s.SleepSpeed:R} m/s for {s.SleepTime:R} s"));
        }
        if (s.Air is { } air)
        {
            var gust = air.Gust is { } g ? Invariant($", a gust of {g.WaveCount} wave{(g.WaveCount == 1 ? string.Empty : "s")}") : string.Empty;
            text.AppendLine(Invariant($"air: {air.Density:R} kg/m^3 at [{air.Velocity.X:R}, {air.Velocity.Y:R}, {air.Velocity.Z:R}] m/s, C_d {air.DragCoefficient:R}, C_l {air.LiftCoefficient:R}{gust}"));
        }

        var integrator = s.Integrator + (IntegratorCatalog.IsPositionBased(s.Integrator) ? Invariant($" ({s.Substeps} substeps)") : string.Empty)
            + (IntegratorCatalog.IsAdaptive(s.Integrator) ? Invariant($" (tolerance {s.Tolerance:R})") : string.Empty);
        text.Append(Invariant($"integrator: {integrator}, dt = {s.TimeStep:R} s, duration {s.Duration:R} s"));
        return text.ToString();
    }

    private ParticleWorld Build(out Dictionary<string, int> counts)
    {
        var world = new ParticleWorld(ParticleCount) { SleepSpeed = Settings.SleepSpeed, SleepTime = Settings.SleepTime };
        var builder = new SceneBuilder(world, File, Settings);
        try
        {
            foreach (var o in _objects)
            {
                o.AddParticles(builder);
            }

            foreach (var o in _objects)
            {
                o.AddElements(builder);
            }

            foreach (var c in _colliders)
            {
                builder.AddObstacle(c.CreateObstacle());
            }

            builder.Finish(Settings);
        }
        catch (Exception e) when (e is ArgumentException or InvalidOperationException)
        {
            // The loader checks everything the core checks; this is the net under it, so that nothing else escapes.
            throw new SceneException(File, string.Empty, 0, 0, string.Empty, "cannot be built: " + e.Message.Split('\n')[0]);
        }

        counts = builder.Counts;
        return world;
    }

    private static Scene Read(JsonDocument document, string directory)
    {
        var root = document.Root;
        if (root.Kind != JsonKind.Object)
        {
            throw new SceneException(document.File, string.Empty, root.Line, root.Column, root.Text(),
                "a scene is a JSON object such as {\"objects\": [...], \"colliders\": [...]}, not " + root.KindName());
        }

        var reader = new ObjectReader(document, root, string.Empty, "a scene");
        var settings = ReadSettings(reader);
        var kinds = SceneKinds.Default;
        var objects = new List<SceneObject>();
        var names = new List<string>();
        long particles = 0;
        foreach (var (item, path) in List(reader, "objects"))
        {
            var objectReader = Typed(document, item, path, kinds.Names(colliders: false), "object", out var type);
            if (!kinds.Objects.TryGetValue(type, out var kind))
            {
                throw UnknownType(document, objectReader, type, kinds, colliders: false);
            }

            var read = kind.Read(objectReader, new SceneReadContext(document.File, directory, (int)particles));
            objectReader.Finish();
            particles += read.ParticleCount;
            if (particles > ParticleWorld.MaxParticles)
            {
                throw objectReader.ObjectError(Invariant(
                    $"brings the scene to {particles:N0} particles; a scene holds at most {ParticleWorld.MaxParticles:N0} (the world's limit)"));
            }

            objects.Add(read);
            names.Add(type);
        }

        var colliders = new List<SceneCollider>();
        foreach (var (item, path) in List(reader, "colliders"))
        {
            var colliderReader = Typed(document, item, path, kinds.Names(colliders: true), "collider", out var type);
            if (!kinds.Colliders.TryGetValue(type, out var kind))
            {
                throw UnknownType(document, colliderReader, type, kinds, colliders: true);
            }

            colliders.Add(kind.Read(colliderReader, new SceneReadContext(document.File, directory, (int)particles)));
            colliderReader.Finish();
        }

        reader.Finish();
        var check = new SceneIndexCheck(document.File, (int)particles);
        foreach (var o in objects)
        {
            o.CheckIndices(check);
        }

        return new Scene(document.File, settings, objects, colliders, (int)particles, names);
    }

    private static SceneSettings ReadSettings(ObjectReader reader)
    {
        var settings = new SceneSettings
        {
            Gravity = reader.Vector("gravity", new Vector3d(0, -Forces.Gravity.StandardAcceleration, 0), "m/s^2"),
            Drag = reader.Number("drag", 0.0, ValueRule.NonNegative, "N s/m"),
            TimeStep = reader.Number("dt", SceneSettings.DefaultTimeStep, ValueRule.Positive, "s"),
            Duration = reader.Number("duration", SceneSettings.DefaultDuration, ValueRule.Positive, "s"),
        };
        ReadIntegrator(reader, settings);
        ReadParticleCollisions(reader, settings);
        ReadAir(reader, settings);
        ReadSleep(reader, settings);

        return settings;
    }

    private static void ReadIntegrator(ObjectReader reader, SceneSettings settings)
    {
        if (reader.Get("integrator") is not { } value)
        {
            return;
        }

        JsonValue nameAt;
        if (value.Kind == JsonKind.String)
        {
            nameAt = value;
        }
        else if (value.Kind == JsonKind.Object)
        {
            var options = new ObjectReader(reader.Document, value, "integrator", "the integrator");
            nameAt = options.Get("name") ?? throw options.ObjectError($"the integrator needs \"name\": one of {string.Join(", ", IntegratorCatalog.Names)}");
            var substeps = options.Number("substeps", Xpbd.DefaultSubsteps, ValueRule.Positive, string.Empty);
            if (substeps != Math.Floor(substeps) || substeps > Xpbd.MaxSubsteps)
            {
                throw options.Error(options.Get("substeps")!.Value, "integrator.substeps", $"must be a whole number from 1 to {Xpbd.MaxSubsteps}");
            }

            settings.Substeps = (int)substeps;
            settings.Tolerance = options.Number("tolerance", 1e-8, ValueRule.Positive, string.Empty);
            if (settings.Tolerance < DormandPrince45.MinTolerance)
            {
                throw options.Error(options.Get("tolerance")!.Value, "integrator.tolerance", Invariant($"must be at least {DormandPrince45.MinTolerance:R} (100 machine epsilons)"));
            }

            options.Finish();
        }
        else
        {
            throw reader.Error(value, "integrator", "must be a name such as \"rk4\" or an object {\"name\", \"substeps\", \"tolerance\"}");
        }

        var path = value.Kind == JsonKind.String ? "integrator" : "integrator.name";
        if (nameAt.Kind != JsonKind.String || !IntegratorCatalog.Names.Contains(nameAt.String))
        {
            var near = nameAt.Kind == JsonKind.String ? ObjectReader.Near(nameAt.String, IntegratorCatalog.Names) : null;
            throw reader.Error(nameAt, path, $"is not an integrator{(near is null ? string.Empty : $" (did you mean '{near}'?)")}; expected one of: {string.Join(", ", IntegratorCatalog.Names)}");
        }

        settings.Integrator = nameAt.String;
    }

    private static void ReadSleep(ObjectReader reader, SceneSettings settings)
    {
        if (reader.Object("sleep", "sleeping") is not { } sleep)
        {
            return;
        }

        settings.SleepSpeed = sleep.Number("speed", null, ValueRule.Positive, "m/s");
        settings.SleepTime = sleep.Number("time", ParticleWorld.DefaultSleepTime, ValueRule.Positive, "s");
        sleep.Finish();
        if (!IntegratorCatalog.IsPositionBased(settings.Integrator))
        {
            throw reader.Error(reader.Get("sleep")!.Value, "sleep", $"needs xpbd: the integrator is {settings.Integrator}, under which nothing sleeps");
        }
    }

    private static void ReadAir(ObjectReader reader, SceneSettings settings)
    {
        if (reader.Object("air", "the air") is not { } air)
        {
            return;
        }

        settings.Air = new Air(
            air.Number("density", Air.StandardDensity, ValueRule.NonNegative, "kg/m^3"),
            air.Vector("velocity", Vector3d.Zero, "m/s"),
            air.Number("drag", 1.0, ValueRule.NonNegative, string.Empty),
            air.Number("lift", 0.0, ValueRule.NonNegative, string.Empty));
        if (air.Get("gust") is { } gust)
        {
            if (gust.Kind != JsonKind.Array || gust.Count == 0)
            {
                throw air.Error(gust, "air.gust", "must be a list of one or more waves {\"amplitude\": [ax, ay, az], \"frequency\": f, \"waveVector\": [kx, ky, kz], \"phase\": phi}");
            }

            var waves = new GustWave[gust.Count];
            var i = 0;
            foreach (var element in gust.Elements())
            {
                var path = ObjectReader.Index("air.gust", i);
                if (element.Kind != JsonKind.Object)
                {
                    throw air.Error(element, path, "must be a wave {\"amplitude\": [ax, ay, az], \"frequency\": f, \"waveVector\": [kx, ky, kz], \"phase\": phi}");
                }

                var wave = new ObjectReader(reader.Document, element, path, "a gust's wave");
                waves[i++] = new GustWave(
                    wave.Vector("amplitude", null, "m/s"),
                    wave.Number("frequency", null, ValueRule.NonNegative, "Hz"),
                    wave.Vector("waveVector", Vector3d.Zero, "rad/m"),
                    wave.Number("phase", 0.0, ValueRule.Finite, "rad"));
                wave.Finish();
            }

            settings.Air.Gust = new Gust(waves);
        }

        air.Finish();
    }

    private static void ReadParticleCollisions(ObjectReader reader, SceneSettings settings)
    {
        if (reader.Get("particleCollisions") is not { } value)
        {
            return;
        }

        if (value.IsBoolean)
        {
            settings.ParticleCollisions = value.Kind == JsonKind.True;
            return;
        }

        if (value.Kind != JsonKind.Object)
        {
            throw reader.Error(value, "particleCollisions", "must be true, false, or {\"restitution\": e, \"friction\": mu} (collisions on, with these)");
        }

        var options = new ObjectReader(reader.Document, value, "particleCollisions", "particleCollisions");
        settings.ParticleCollisions = true;
        settings.ParticleRestitution = options.Number("restitution", 0.0, ValueRule.Fraction, string.Empty);
        settings.ParticleFriction = options.Number("friction", 0.0, ValueRule.NonNegative, string.Empty);
        options.Finish();
    }

    // The elements of a top-level list ("objects", "colliders"), each with its path.
    private static IEnumerable<(JsonValue Item, string Path)> List(ObjectReader reader, string key)
    {
        if (reader.Get(key) is not { } value)
        {
            yield break;
        }

        if (value.Kind != JsonKind.Array)
        {
            throw reader.Error(value, key, $"must be a list [...] of {key}, not {value.KindName()}");
        }

        var i = 0;
        foreach (var item in value.Elements())
        {
            yield return (item, ObjectReader.Index(key, i++));
        }
    }

    // A reader for one element of "objects" or "colliders", with its "type".
    private static ObjectReader Typed(JsonDocument document, JsonValue item, string path, IEnumerable<string> names, string what, out string type)
    {
        if (item.Kind != JsonKind.Object)
        {
            throw new SceneException(document.File, path, item.Line, item.Column, item.Text(),
                $"each {what} is an object {{\"type\": ..., ...}}, not {item.KindName()}");
        }

        var probe = new ObjectReader(document, item, path, "an " + what);
        var typeValue = probe.Get("type") ?? throw probe.ObjectError($"each {what} needs a \"type\": one of {string.Join(", ", names)}");
        if (typeValue.Kind != JsonKind.String)
        {
            throw probe.Error(typeValue, probe.PathOf("type"), $"must be a string: one of {string.Join(", ", names)}");
        }

        type = typeValue.String;
        var reader = new ObjectReader(document, item, path, $"a {type} {what}");
        reader.Know("type");
        return reader;
    }

    private static SceneException UnknownType(JsonDocument document, ObjectReader reader, string type, SceneKinds kinds, bool colliders)
    {
        var at = reader.Get("type")!.Value;
        var near = ObjectReader.Near(type, kinds.Names(colliders));
        return new SceneException(document.File, reader.PathOf("type"), at.Line, at.Column, at.Text(),
            $"is not a kind of {(colliders ? "collider" : "object")}{(near is null ? string.Empty : $" (did you mean '{near}'?)")}; expected one of: {string.Join(", ", kinds.Names(colliders))}");
    }

    private static string Invariant(FormattableString text) => text.ToString(CultureInfo.InvariantCulture);
}
