using System;
using System.Collections.Generic;
using System.Globalization;
using System.IO;
using System.Text;
using ParticlePhysics.Scenes.Text;

namespace ParticlePhysics.Scenes.Json;

/// <summary>
/// A bounded JSON reader for scene files: JSON with <c>//</c> comments and trailing commas, exact 1-based lines and
/// columns, and limits on size, depth, values and string length, so that no input makes it allocate more than about
/// 25 bytes per value of a file of at most <see cref="MaxChars"/> characters, or recurse deeper than
/// <see cref="MaxDepth"/>. Every problem is a <see cref="SceneException"/> naming the line, the column and the JSON
/// path where it was found.
/// </summary>
/// <remarks>
/// Written by hand because netstandard2.1 has no System.Text.Json in the box (the package adds four assemblies that
/// Unity projects often already hold in other versions) and its reader reports byte offsets, not columns. One concept
/// in one file of some 600 lines: the grammar and the reading of its tokens share one character stream, its position,
/// line and column, and every error names all three.
/// </remarks>
internal sealed class JsonParser
{
    /// <summary>The largest scene file, in characters (64 MiB): a bigger file is refused before it is read.</summary>
    public const int MaxChars = 64 << 20;

    /// <summary>The most values a file may hold (2^22, about a million particles written out).</summary>
    public const int MaxValues = 1 << 22;

    /// <summary>The deepest nesting of arrays and objects.</summary>
    public const int MaxDepth = 64;

    /// <summary>The longest string, in characters.</summary>
    public const int MaxStringLength = 1 << 16;

    private const int MaxNumberLength = 100;

    private readonly TextReader _reader;
    private readonly string _file;
    private readonly char[] _buffer = new char[1 << 14];
    private readonly List<object> _path = new();
    private readonly List<string> _strings = new();
    private readonly Dictionary<string, int> _stringIndex = new(StringComparer.Ordinal);
    private readonly StringBuilder _text = new();
    private JsonEntry[] _entries = new JsonEntry[256];
    private int _count;
    private int _length;
    private int _position;
    private long _consumed;
    private int _line = 1;
    private int _column = 1;

    private JsonParser(TextReader reader, string file)
    {
        _reader = reader;
        _file = file;
    }

    /// <summary>Parses a file, read as UTF-8.</summary>
    /// <param name="path">Where to read it.</param>
    /// <param name="file">The name to give in messages (as the user wrote it).</param>
    public static JsonDocument ParseFile(string path, string file)
    {
        FileStream stream;
        try
        {
            stream = new FileStream(path, FileMode.Open, FileAccess.Read, FileShare.Read, 1 << 16);
        }
        catch (Exception e) when (e is IOException or UnauthorizedAccessException or ArgumentException or NotSupportedException)
        {
            throw new SceneException(file, string.Empty, 0, 0, string.Empty, "cannot be read: " + e.Message);
        }

        using (stream)
        {
            if (stream.CanSeek && stream.Length > MaxChars)
            {
                throw new SceneException(file, string.Empty, 0, 0, string.Empty, FormattableString.Invariant(
                    $"the file holds {stream.Length:N0} bytes; a scene file may hold at most {MaxChars:N0} (bodies that large belong in OBJ files or generated objects)"));
            }

            using var reader = new StreamReader(stream, new UTF8Encoding(false), detectEncodingFromByteOrderMarks: true, 1 << 14);
            return new JsonParser(reader, file).Parse();
        }
    }

    /// <summary>Parses JSON text.</summary>
    public static JsonDocument ParseText(string text, string file)
    {
        if (text.Length > MaxChars)
        {
            throw new SceneException(file, string.Empty, 0, 0, string.Empty, FormattableString.Invariant(
                $"the text holds {text.Length:N0} characters; a scene may hold at most {MaxChars:N0}"));
        }

        using var reader = new StringReader(text);
        return new JsonParser(reader, file).Parse();
    }

    private JsonDocument Parse()
    {
        SkipSpace();
        if (Peek() < 0)
        {
            throw new SceneException(_file, string.Empty, 0, 0, string.Empty,
                "the file is empty; a scene is a JSON object such as {\"objects\": [...], \"colliders\": [...]}");
        }

        ParseValue(0);
        SkipSpace();
        if (Peek() >= 0)
        {
            throw Fail(_line, _column, Describe(Peek()), "text after the end of the scene's JSON value; a file holds one object");
        }

        return new JsonDocument(_file, _entries, _count, _strings);
    }

    private void ParseValue(int depth)
    {
        var c = Peek();
        int line = _line, column = _column;
        switch (c)
        {
            case '{':
                ParseObject(depth + 1, line, column);
                return;
            case '[':
                ParseArray(depth + 1, line, column);
                return;
            case '"':
                var text = ReadString();
                Add(JsonKind.String, line, column).Extra = Intern(text);
                return;
            case 't':
                ReadWord("true", line, column);
                Add(JsonKind.True, line, column);
                return;
            case 'f':
                ReadWord("false", line, column);
                Add(JsonKind.False, line, column);
                return;
            case 'n':
                ReadWord("null", line, column);
                Add(JsonKind.Null, line, column);
                return;
            case < 0:
                throw Fail(line, column, string.Empty, "the file ends where a value should be");
            default:
                if (c == '-' || (c >= '0' && c <= '9'))
                {
                    Add(JsonKind.Number, line, column).Number = ReadNumber(line, column);
                    return;
                }

                throw Fail(line, column, Describe(c), "expected a value: a number, a string in double quotes, true, false, null, [ or {");
        }
    }

    private void ParseObject(int depth, int line, int column)
    {
        CheckDepth(depth, line, column);
        var at = _count;
        Add(JsonKind.Object, line, column);
        Next();
        var keys = new HashSet<string>(StringComparer.Ordinal);
        var members = 0;
        while (true)
        {
            SkipSpace();
            var c = Peek();
            if (c == '}')
            {
                Next();
                break;
            }

            if (c != '"')
            {
                throw Fail(_line, _column, Describe(c), members == 0
                    ? "expected a key in double quotes or '}'"
                    : "expected a key in double quotes or '}' after ','");
            }

            int keyLine = _line, keyColumn = _column;
            var key = ReadString();
            if (!keys.Add(key))
            {
                _path.Add(key);
                throw Fail(keyLine, keyColumn, string.Empty, "this key appears twice in one object; give each key once");
            }

            Add(JsonKind.String, keyLine, keyColumn).Extra = Intern(key);
            SkipSpace();
            if (Peek() != ':')
            {
                throw Fail(_line, _column, Describe(Peek()), $"expected ':' after the key \"{key}\"");
            }

            Next();
            SkipSpace();
            _path.Add(key);
            ParseValue(depth);
            _path.RemoveAt(_path.Count - 1);
            members++;
            SkipSpace();
            c = Peek();
            if (c == ',')
            {
                Next();
                continue;
            }

            if (c == '}')
            {
                Next();
                break;
            }

            throw Fail(_line, _column, Describe(c), "expected ',' or '}' after a member of an object");
        }

        _entries[at].Count = members;
        _entries[at].Extra = _count;
    }

    private void ParseArray(int depth, int line, int column)
    {
        CheckDepth(depth, line, column);
        var at = _count;
        Add(JsonKind.Array, line, column);
        Next();
        var elements = 0;
        while (true)
        {
            SkipSpace();
            if (Peek() == ']')
            {
                Next();
                break;
            }

            _path.Add(elements);
            ParseValue(depth);
            _path.RemoveAt(_path.Count - 1);
            elements++;
            SkipSpace();
            var c = Peek();
            if (c == ',')
            {
                Next();
                continue;
            }

            if (c == ']')
            {
                Next();
                break;
            }

            throw Fail(_line, _column, Describe(c), "expected ',' or ']' after an element of an array");
        }

        _entries[at].Count = elements;
        _entries[at].Extra = _count;
    }

    private void CheckDepth(int depth, int line, int column)
    {
        if (depth > MaxDepth)
        {
            throw Fail(line, column, string.Empty, $"arrays and objects nested more than {MaxDepth} deep; a scene needs a few levels");
        }
    }

    private ref JsonEntry Add(JsonKind kind, int line, int column)
    {
        if (_count == MaxValues)
        {
            throw Fail(line, column, string.Empty, FormattableString.Invariant(
                $"more than {MaxValues:N0} JSON values; a scene file may hold at most that many (large bodies belong in OBJ files or generated objects)"));
        }

        if (_count == _entries.Length)
        {
            Array.Resize(ref _entries, Math.Min(MaxValues, 2 * _entries.Length));
        }

        ref var entry = ref _entries[_count++];
        entry.Kind = kind;
        entry.Line = line;
        entry.Column = column;
        return ref entry;
    }

    private int Intern(string text)
    {
        if (!_stringIndex.TryGetValue(text, out var index))
        {
            index = _strings.Count;
            _strings.Add(text);
            _stringIndex.Add(text, index);
        }

        return index;
    }

    private string ReadString()
    {
        int line = _line, column = _column;
        Next(); // the opening quote
        _text.Clear();
        while (true)
        {
            var c = Peek();
            if (c < 0)
            {
                throw Fail(line, column, string.Empty, "a string that never ends: the file ends before its closing '\"'");
            }

            if (c == '"')
            {
                Next();
                return _text.ToString();
            }

            if (c < 0x20)
            {
                throw Fail(_line, _column, Describe(c), "a control character (a line break, a tab) inside a string; write it as an escape such as \\n or \\t");
            }

            if (_text.Length == MaxStringLength)
            {
                throw Fail(line, column, string.Empty, FormattableString.Invariant($"a string longer than {MaxStringLength:N0} characters"));
            }

            if (c != '\\')
            {
                _text.Append((char)c);
                Next();
                continue;
            }

            int escapeLine = _line, escapeColumn = _column;
            Next();
            var e = Peek();
            Next();
            switch (e)
            {
                case '"':
                    _text.Append('"');
                    break;
                case '\\':
                    _text.Append('\\');
                    break;
                case '/':
                    _text.Append('/');
                    break;
                case 'b':
                    _text.Append('\b');
                    break;
                case 'f':
                    _text.Append('\f');
                    break;
                case 'n':
                    _text.Append('\n');
                    break;
                case 'r':
                    _text.Append('\r');
                    break;
                case 't':
                    _text.Append('\t');
                    break;
                case 'u':
                    var code = 0;
                    for (var k = 0; k < 4; k++)
                    {
                        var h = Peek();
                        var digit = h >= '0' && h <= '9' ? h - '0' : h >= 'a' && h <= 'f' ? h - 'a' + 10 : h >= 'A' && h <= 'F' ? h - 'A' + 10 : -1;
                        if (digit < 0)
                        {
                            throw Fail(escapeLine, escapeColumn, string.Empty, "\\u must be followed by four hexadecimal digits");
                        }

                        code = (code << 4) | digit;
                        Next();
                    }

                    _text.Append((char)code);
                    break;
                default:
                    throw Fail(escapeLine, escapeColumn, e < 0 ? "the end of the file" : "'\\" + (char)e + "'", "an unknown escape; JSON allows \\\" \\\\ \\/ \\b \\f \\n \\r \\t and \\uXXXX");
            }
        }
    }

    private double ReadNumber(int line, int column)
    {
        // The JSON grammar: -?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?
        _text.Clear();
        if (Peek() == '-')
        {
            Take();
        }

        if (Peek() == '0')
        {
            Take();
            if (IsDigit(Peek()))
            {
                throw Fail(line, column, "'" + _text.ToString() + (char)Peek() + "'", "a number may not start with 0 followed by digits (write 7, not 07)");
            }
        }
        else
        {
            Digits(line, column, "a digit after '-'");
        }

        if (Peek() == '.')
        {
            Take();
            Digits(line, column, "a digit after the decimal point");
        }

        if (Peek() is 'e' or 'E')
        {
            Take();
            if (Peek() is '+' or '-')
            {
                Take();
            }

            Digits(line, column, "a digit in the exponent");
        }

        var c = Peek();
        if (IsLetter(c) || c == '.')
        {
            throw Fail(line, column, "'" + _text.ToString() + (char)c + "...'", "not a number: JSON numbers are written like -1.5e3 (no NaN, Infinity or hexadecimal)");
        }

        var text = _text.ToString();
        if (!DecimalParser.TryParse(text.AsSpan(), out var value))
        {
            throw Fail(line, column, text, "a number beyond the range of a double (about 1.8e308)");
        }

        return value;
    }

    private void Digits(int line, int column, string what)
    {
        if (!IsDigit(Peek()))
        {
            var found = Peek() < 0 ? "the end of the file" : Describe(Peek());
            throw Fail(line, column, found, $"expected {what} in '{_text}'");
        }

        while (IsDigit(Peek()))
        {
            Take();
        }
    }

    private void Take()
    {
        if (_text.Length == MaxNumberLength)
        {
            throw Fail(_line, _column, string.Empty, $"a number longer than {MaxNumberLength} characters");
        }

        _text.Append((char)Peek());
        Next();
    }

    private void ReadWord(string word, int line, int column)
    {
        foreach (var expected in word)
        {
            if (Peek() != expected)
            {
                throw Fail(line, column, "'" + ReadBareWord() + "'", "not a JSON value: keys and strings need double quotes, and the only bare words are true, false and null");
            }

            Next();
        }

        if (IsLetter(Peek()) || IsDigit(Peek()))
        {
            throw Fail(line, column, "'" + word + ReadBareWord() + "'", "not a JSON value: keys and strings need double quotes, and the only bare words are true, false and null");
        }
    }

    private string ReadBareWord()
    {
        var word = new StringBuilder();
        while (word.Length < 40 && (IsLetter(Peek()) || IsDigit(Peek()) || Peek() == '_'))
        {
            word.Append((char)Peek());
            Next();
        }

        return word.ToString();
    }

    private void SkipSpace()
    {
        while (true)
        {
            var c = Peek();
            if (c is ' ' or '\t' or '\n' or '\r')
            {
                Next();
                continue;
            }

            if (c == '/')
            {
                int line = _line, column = _column;
                Next();
                if (Peek() != '/')
                {
                    throw Fail(line, column, string.Empty, "only // comments are allowed (to the end of the line)");
                }

                while (Peek() >= 0 && Peek() != '\n')
                {
                    Next();
                }

                continue;
            }

            if (c == '\uFEFF' && _consumed == 0)
            {
                Next();
                continue;
            }

            return;
        }
    }

    private int Peek()
    {
        if (_position == _length)
        {
            _length = _reader.Read(_buffer, 0, _buffer.Length);
            _position = 0;
            if (_length <= 0)
            {
                _length = 0;
                return -1;
            }
        }

        return _buffer[_position];
    }

    private void Next()
    {
        if (Peek() < 0)
        {
            return;
        }

        if (_buffer[_position] == '\n')
        {
            _line++;
            _column = 1;
        }
        else
        {
            _column++;
        }

        _position++;
        if (++_consumed > MaxChars)
        {
            throw Fail(_line, _column, string.Empty, FormattableString.Invariant($"a scene file may hold at most {MaxChars:N0} characters"));
        }
    }

    private static bool IsDigit(int c) => c >= '0' && c <= '9';

    private static bool IsLetter(int c) => (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');

    private static string Describe(int c) => c switch
    {
        < 0 => "the end of the file",
        '\n' => "a line break",
        '\r' => "a carriage return",
        '\t' => "a tab",
        < 0x20 => FormattableString.Invariant($"the control character U+{c:X4}"),
        '\'' => "' (strings and keys take double quotes)",
        _ => "'" + (char)c + "'",
    };

    // found: what stood there (already quoted or described), or empty.
    private SceneException Fail(int line, int column, string found, string problem) =>
        new(_file, PathText(_path), line, column, string.Empty, "malformed JSON: " + problem + (found.Length > 0 ? ", found " + found : string.Empty));

    /// <summary>A JSON path: keys joined by '.', array indices in brackets (<c>objects[2].pairs[0]</c>).</summary>
    public static string PathText(IReadOnlyList<object> path)
    {
        var text = new StringBuilder();
        foreach (var part in path)
        {
            if (part is int index)
            {
                text.Append('[').Append(index.ToString(CultureInfo.InvariantCulture)).Append(']');
            }
            else
            {
                if (text.Length > 0)
                {
                    text.Append('.');
                }

                text.Append((string)part);
            }
        }

        return text.ToString();
    }
}
