using System;
using System.Collections.Generic;
using System.Globalization;
using System.Linq;
using ParticlePhysics.Scenes.Json;

namespace ParticlePhysics.Scenes.Kinds;

/// <summary>What a number of a scene may be.</summary>
internal enum ValueRule
{
    /// <summary>Any finite number (positions, velocities, forces).</summary>
    Finite,

    /// <summary>A finite number &gt;= 0 (stiffness, damping, drag, radii, friction).</summary>
    NonNegative,

    /// <summary>A positive finite number (dt, duration, lengths, a sphere's radius).</summary>
    Positive,

    /// <summary>A mass: positive and finite, its inverse finite too.</summary>
    Mass,

    /// <summary>A number from 0 to 1 (restitution).</summary>
    Fraction,
}

/// <summary>
/// A particle index read from a scene, with where it was written, so that a check made once every object is read (an
/// index beyond the scene's particles) still names its line and column.
/// </summary>
internal readonly struct IndexRef
{
    public IndexRef(int value, JsonValue where, string path)
    {
        Value = value;
        Where = where;
        Path = path;
    }

    /// <summary>The index.</summary>
    public int Value { get; }

    /// <summary>Where it was written.</summary>
    public JsonValue Where { get; }

    /// <summary>Its JSON path.</summary>
    public string Path { get; }
}

/// <summary>
/// Reads one JSON object of a scene (the file, an object of <c>objects</c>, a collider, a nested option) as a kind
/// expects it: each key through a typed getter that checks the value against its rule and reports a bad one with its
/// JSON path, line, column and what is allowed. The keys a kind asks for are the keys it knows: <see cref="Finish"/>
/// refuses any other (a typo must not be ignored).
/// </summary>
internal sealed class ObjectReader
{
    private readonly Dictionary<string, (JsonValue Key, JsonValue Value)> _members = new(StringComparer.Ordinal);
    private readonly List<(JsonValue Key, JsonValue Value)> _order;
    private readonly List<string> _known = new();

    public ObjectReader(JsonDocument document, JsonValue value, string path, string what)
    {
        Document = document;
        Value = value;
        Path = path;
        What = what;
        _order = value.Members();
        foreach (var member in _order)
        {
            _members[member.Key.String] = member;
        }
    }

    public JsonDocument Document { get; }

    /// <summary>The object itself.</summary>
    public JsonValue Value { get; }

    /// <summary>Its JSON path (<c>objects[2]</c>).</summary>
    public string Path { get; }

    /// <summary>What it is, for messages: "a springs object", "the scene".</summary>
    public string What { get; }

    /// <summary>The path of one of its keys.</summary>
    public string PathOf(string key) => Path.Length == 0 ? key : Path + "." + key;

    /// <summary>True when the object has <paramref name="key"/> (which becomes a known key).</summary>
    public bool Has(string key)
    {
        Know(key);
        return _members.ContainsKey(key);
    }

    /// <summary>The value of <paramref name="key"/>, or null (the key becomes a known key either way).</summary>
    public JsonValue? Get(string key)
    {
        Know(key);
        return _members.TryGetValue(key, out var member) ? member.Value : null;
    }

    /// <summary>An error about the value at <paramref name="where"/>, whose path is <paramref name="path"/>.</summary>
    public SceneException Error(JsonValue where, string path, string problem, bool showValue = true) =>
        new(Document.File, path, where.Line, where.Column, showValue ? where.Text() : string.Empty, problem);

    /// <summary>An error about the object as a whole (a missing key, two keys that exclude each other).</summary>
    public SceneException ObjectError(string problem) =>
        new(Document.File, Path, Value.Line, Value.Column, string.Empty, problem);

    /// <summary>A number: <paramref name="defaultValue"/> when absent, an error when absent without one.</summary>
    public double Number(string key, double? defaultValue, ValueRule rule, string unit)
    {
        var value = Get(key);
        if (value is not { } v)
        {
            return defaultValue ?? throw Missing(key, Allowed(rule, unit));
        }

        return CheckNumber(v, PathOf(key), rule, unit);
    }

    /// <summary>A boolean, or <paramref name="defaultValue"/>.</summary>
    public bool Boolean(string key, bool defaultValue)
    {
        var value = Get(key);
        if (value is not { } v)
        {
            return defaultValue;
        }

        if (!v.IsBoolean)
        {
            throw Error(v, PathOf(key), $"must be true or false, not {v.KindName()}");
        }

        return v.Kind == JsonKind.True;
    }

    /// <summary>A string, or null when absent.</summary>
    public string? String(string key)
    {
        var value = Get(key);
        if (value is not { } v)
        {
            return null;
        }

        if (v.Kind != JsonKind.String)
        {
            throw Error(v, PathOf(key), $"must be a string in double quotes, not {v.KindName()}");
        }

        return v.String;
    }

    /// <summary>A vector [x, y, z] of finite numbers, or <paramref name="defaultValue"/> (an error when absent without one).</summary>
    public Vector3d Vector(string key, Vector3d? defaultValue, string unit)
    {
        var value = Get(key);
        if (value is not { } v)
        {
            return defaultValue ?? throw Missing(key, $"[x, y, z] in {unit}");
        }

        return CheckVector(v, PathOf(key), unit);
    }

    /// <summary>A list of vectors [[x, y, z], ...]; null when absent.</summary>
    public List<(Vector3d Vector, JsonValue Where)>? Vectors(string key, string unit)
    {
        var value = Get(key);
        if (value is not { } v)
        {
            return null;
        }

        var path = PathOf(key);
        RequireArray(v, path, $"a list of [x, y, z] in {unit}");
        var list = new List<(Vector3d, JsonValue)>(v.Count);
        var i = 0;
        foreach (var element in v.Elements())
        {
            list.Add((CheckVector(element, Index(path, i++), unit), element));
        }

        return list;
    }

    /// <summary>A list of numbers; null when absent.</summary>
    public List<double>? Numbers(string key, ValueRule rule, string unit)
    {
        var value = Get(key);
        if (value is not { } v)
        {
            return null;
        }

        var path = PathOf(key);
        RequireArray(v, path, "a list of numbers " + Allowed(rule, unit));
        var list = new List<double>(v.Count);
        var i = 0;
        foreach (var element in v.Elements())
        {
            list.Add(CheckNumber(element, Index(path, i++), rule, unit));
        }

        return list;
    }

    /// <summary>A list of particle indices (whole numbers &gt;= 0), checked against their range later; null when absent.</summary>
    public List<IndexRef>? Indices(string key)
    {
        var value = Get(key);
        if (value is not { } v)
        {
            return null;
        }

        var path = PathOf(key);
        RequireArray(v, path, "a list of particle indices");
        var list = new List<IndexRef>(v.Count);
        var i = 0;
        foreach (var element in v.Elements())
        {
            var at = Index(path, i++);
            list.Add(new IndexRef(CheckIndex(element, at), element, at));
        }

        return list;
    }

    /// <summary>A list of index pairs [[i, j], ...] of two different particles; null when absent.</summary>
    public List<(IndexRef First, IndexRef Second)>? Pairs(string key)
    {
        var value = Get(key);
        if (value is not { } v)
        {
            return null;
        }

        var path = PathOf(key);
        RequireArray(v, path, "a list of pairs [i, j] of particle indices");
        var list = new List<(IndexRef, IndexRef)>(v.Count);
        var k = 0;
        foreach (var pair in v.Elements())
        {
            var at = Index(path, k++);
            if (pair.Kind != JsonKind.Array || pair.Count != 2)
            {
                throw Error(pair, at, "must be a pair [i, j] of particle indices");
            }

            var ends = pair.Elements();
            var first = new IndexRef(CheckIndex(ends[0], at + "[0]"), ends[0], at + "[0]");
            var second = new IndexRef(CheckIndex(ends[1], at + "[1]"), ends[1], at + "[1]");
            if (first.Value == second.Value)
            {
                throw Error(pair, at, "joins a particle to itself; a pair needs two different particles");
            }

            list.Add((first, second));
        }

        return list;
    }

    /// <summary>A nested object, read by a reader of its own (the caller finishes it); null when absent.</summary>
    public ObjectReader? Object(string key, string what)
    {
        var value = Get(key);
        if (value is not { } v)
        {
            return null;
        }

        if (v.Kind != JsonKind.Object)
        {
            throw Error(v, PathOf(key), $"must be an object {{...}}, not {v.KindName()}");
        }

        return new ObjectReader(Document, v, PathOf(key), what);
    }

    /// <summary>Refuses the first key no getter asked for: a typo must not be ignored.</summary>
    public void Finish()
    {
        foreach (var (key, _) in _order)
        {
            if (!_known.Contains(key.String))
            {
                var name = key.String;
                var near = Near(name, _known);
                throw new SceneException(
                    Document.File,
                    PathOf(name),
                    key.Line,
                    key.Column,
                    string.Empty,
                    $"unknown key for {What}{(near is null ? string.Empty : $" (did you mean '{near}'?)")}; its keys are: {string.Join(", ", _known)}");
            }
        }
    }

    /// <summary>Says that <paramref name="key"/> belongs to this object (for keys read through <see cref="Get"/> elsewhere).</summary>
    public void Know(string key)
    {
        if (!_known.Contains(key))
        {
            _known.Add(key);
        }
    }

    /// <summary>Checks a number against a rule.</summary>
    public double CheckNumber(JsonValue v, string path, ValueRule rule, string unit)
    {
        if (!v.IsNumber)
        {
            throw Error(v, path, $"must be a number {Allowed(rule, unit)}, not {v.KindName()}");
        }

        var x = v.Number;
        var ok = rule switch
        {
            ValueRule.NonNegative => x >= 0,
            ValueRule.Positive => x > 0,
            ValueRule.Mass => x > 0 && !double.IsInfinity(1.0 / x),
            ValueRule.Fraction => x >= 0 && x <= 1,
            _ => true,
        };
        if (!ok)
        {
            throw Error(v, path, "must be " + Allowed(rule, unit).TrimStart('('));
        }

        return x;
    }

    /// <summary>What a rule allows, in words, with the unit.</summary>
    public static string Allowed(ValueRule rule, string unit)
    {
        var units = unit.Length == 0 ? string.Empty : $" ({unit})";
        return rule switch
        {
            ValueRule.NonNegative => "a number >= 0" + units,
            ValueRule.Positive => "a positive number" + units,
            ValueRule.Mass => "a positive number" + units + " whose inverse is finite (at least 5.6e-309)",
            ValueRule.Fraction => "a number from 0 to 1",
            _ => "a finite number" + units,
        };
    }

    /// <summary>The path of element <paramref name="index"/> of the array at <paramref name="path"/>.</summary>
    public static string Index(string path, int index) => path + "[" + index.ToString(CultureInfo.InvariantCulture) + "]";

    /// <summary>The known word nearest <paramref name="word"/> (at most two edits, or a different case), or null.</summary>
    public static string? Near(string word, IEnumerable<string> known)
    {
        string? best = null;
        var bestDistance = int.MaxValue;
        foreach (var candidate in known)
        {
            var d = string.Equals(candidate, word, StringComparison.OrdinalIgnoreCase) ? 0 : Distance(word, candidate);
            if (d < bestDistance)
            {
                (best, bestDistance) = (candidate, d);
            }
        }

        return bestDistance <= Math.Max(1, Math.Min(2, word.Length / 3)) ? best : null;
    }

    private Vector3d CheckVector(JsonValue v, string path, string unit)
    {
        if (v.Kind != JsonKind.Array || v.Count != 3)
        {
            throw Error(v, path, $"must be [x, y, z], three numbers in {unit}");
        }

        var e = v.Elements();
        return new Vector3d(
            CheckNumber(e[0], path + "[0]", ValueRule.Finite, unit),
            CheckNumber(e[1], path + "[1]", ValueRule.Finite, unit),
            CheckNumber(e[2], path + "[2]", ValueRule.Finite, unit));
    }

    private int CheckIndex(JsonValue v, string path)
    {
        if (!v.IsNumber || v.Number < 0 || v.Number != Math.Floor(v.Number) || v.Number > int.MaxValue)
        {
            throw Error(v, path, "must be a particle index: a whole number >= 0");
        }

        return (int)v.Number;
    }

    private void RequireArray(JsonValue v, string path, string what)
    {
        if (v.Kind != JsonKind.Array)
        {
            throw Error(v, path, $"must be {what}, not {v.KindName()}");
        }
    }

    private SceneException Missing(string key, string what) =>
        ObjectError($"{What} needs \"{key}\": {what}");

    // Levenshtein distance, for the suggestions of a mistyped key (keys are short).
    private static int Distance(string a, string b)
    {
        if (a.Length > 64 || b.Length > 64)
        {
            return int.MaxValue;
        }

        var previous = Enumerable.Range(0, b.Length + 1).ToArray();
        var current = new int[b.Length + 1];
        for (var i = 1; i <= a.Length; i++)
        {
            current[0] = i;
            for (var j = 1; j <= b.Length; j++)
            {
                var cost = a[i - 1] == b[j - 1] ? 0 : 1;
                current[j] = Math.Min(Math.Min(current[j - 1] + 1, previous[j] + 1), previous[j - 1] + cost);
            }

            (previous, current) = (current, previous);
        }

        return previous[b.Length];
    }
}
