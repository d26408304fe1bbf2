using System;
using System.Collections.Generic;
using System.Globalization;

namespace ParticlePhysics.Scenes.Json;

/// <summary>The kinds of JSON value.</summary>
internal enum JsonKind : byte
{
    Null,
    False,
    True,
    Number,
    String,
    Array,
    Object,
}

/// <summary>
/// One value of a parsed document, in document order (a container is followed by its children; an object's children
/// are key, value, key, value...). 24 bytes whatever the value, so that a file of many small numbers stays small.
/// </summary>
internal struct JsonEntry
{
    /// <summary>A number's value.</summary>
    public double Number;

    /// <summary>Where the value starts: line and column, from 1.</summary>
    public int Line;

    /// <summary>Where the value starts: line and column, from 1.</summary>
    public int Column;

    /// <summary>A string's index in <see cref="JsonDocument.Strings"/>; a container's end (the index after its last descendant).</summary>
    public int Extra;

    /// <summary>A container's number of elements (an array) or members (an object).</summary>
    public int Count;

    /// <summary>What the value is.</summary>
    public JsonKind Kind;
}

/// <summary>A parsed JSON file: its values as a flat list (<see cref="JsonEntry"/>) and its strings.</summary>
internal sealed class JsonDocument
{
    public JsonDocument(string file, JsonEntry[] entries, int count, List<string> strings)
    {
        File = file;
        Entries = entries;
        EntryCount = count;
        Strings = strings;
    }

    /// <summary>The file, as the user named it (for messages).</summary>
    public string File { get; }

    public JsonEntry[] Entries { get; }

    public int EntryCount { get; }

    public List<string> Strings { get; }

    /// <summary>The top-level value.</summary>
    public JsonValue Root => new(this, 0);
}

/// <summary>A view of one value of a <see cref="JsonDocument"/>.</summary>
internal readonly struct JsonValue
{
    private readonly JsonDocument _document;
    private readonly int _index;

    public JsonValue(JsonDocument document, int index)
    {
        _document = document;
        _index = index;
    }

    private ref JsonEntry Entry => ref _document.Entries[_index];

    public JsonKind Kind => Entry.Kind;

    public int Line => Entry.Line;

    public int Column => Entry.Column;

    public double Number => Entry.Number;

    public string String => _document.Strings[Entry.Extra];

    /// <summary>The number of elements of an array or members of an object.</summary>
    public int Count => Entry.Count;

    public bool IsNumber => Kind == JsonKind.Number;

    public bool IsBoolean => Kind is JsonKind.True or JsonKind.False;

    /// <summary>The elements of an array, in order.</summary>
    public List<JsonValue> Elements()
    {
        var list = new List<JsonValue>(Count);
        var end = Entry.Extra;
        for (var i = _index + 1; i < end; i = Next(i))
        {
            list.Add(new JsonValue(_document, i));
        }

        return list;
    }

    /// <summary>The members of an object, in order: each key (a string value, for its position) and its value.</summary>
    public List<(JsonValue Key, JsonValue Value)> Members()
    {
        var list = new List<(JsonValue, JsonValue)>(Count);
        var end = Entry.Extra;
        for (var i = _index + 1; i < end; i = Next(i + 1))
        {
            list.Add((new JsonValue(_document, i), new JsonValue(_document, i + 1)));
        }

        return list;
    }

    /// <summary>The value as the file writes it, shortened, for messages.</summary>
    public string Text()
    {
        switch (Kind)
        {
            case JsonKind.Null:
                return "null";
            case JsonKind.True:
                return "true";
            case JsonKind.False:
                return "false";
            case JsonKind.Number:
                return Number.ToString("R", CultureInfo.InvariantCulture);
            case JsonKind.String:
                var s = String;
                return "\"" + (s.Length > 40 ? s.Substring(0, 40) + "..." : s) + "\"";
            case JsonKind.Array:
                return Count == 0 ? "[]" : Count <= 4 && AllScalars() ? "[" + string.Join(", ", Elements().ConvertAll(e => e.Text())) + "]" : $"[... {Count} elements]";
            default:
                return Count == 0 ? "{}" : "{...}";
        }
    }

    /// <summary>A word for the kind, for messages: "a number", "an array", ...</summary>
    public string KindName() => Kind switch
    {
        JsonKind.Null => "null",
        JsonKind.True or JsonKind.False => "a boolean",
        JsonKind.Number => "a number",
        JsonKind.String => "a string",
        JsonKind.Array => "an array",
        _ => "an object",
    };

    private bool AllScalars()
    {
        foreach (var e in Elements())
        {
            if (e.Kind is JsonKind.Array or JsonKind.Object)
            {
                return false;
            }
        }

        return true;
    }

    private int Next(int i)
    {
        ref var e = ref _document.Entries[i];
        return e.Kind is JsonKind.Array or JsonKind.Object ? e.Extra : i + 1;
    }
}
