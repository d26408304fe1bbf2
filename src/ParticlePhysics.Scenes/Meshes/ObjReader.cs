using System;
using System.Buffers.Text;
using System.IO;
using System.Text;
using ParticlePhysics.Scenes.Text;

namespace ParticlePhysics.Scenes.Meshes;

/// <summary>
/// Reads the triangles of a Wavefront OBJ file: <c>v x y z</c> lines (a fourth w or three colour components are
/// allowed and ignored) and <c>f</c> lines of three or more vertices, each written <c>v</c>, <c>v/vt</c>,
/// <c>v//vn</c> or <c>v/vt/vn</c>, with 1-based or negative (counted back from the last vertex so far) indices; a face
/// of n vertices is fanned into the triangles (0, k, k + 1). <c>vt</c>, <c>vn</c>, <c>o</c>, <c>g</c>, <c>s</c>,
/// <c>usemtl</c>, <c>mtllib</c> and <c>#</c> comments are ignored; any other statement is an error, as is a malformed
/// number or an index outside the vertices, each naming the file and the line.
/// </summary>
/// <remarks>
/// It reads bytes in large blocks and parses each line in place (numbers with the correctly rounded <see cref="DecimalParser"/>, the same bits on every runtime), allocating
/// only the growing vertex and triangle arrays: the benchmarks' <c>obj</c> mode measures its throughput.
/// </remarks>
public static class ObjReader
{
    /// <summary>The most vertices a mesh may have (the contract's largest scene, 10^7 particles).</summary>
    public const int MaxVertices = 10_000_000;

    /// <summary>The most triangles a mesh may have.</summary>
    public const int MaxTriangles = 20_000_000;

    /// <summary>The longest line, in bytes.</summary>
    public const int MaxLineBytes = 1 << 20;

    /// <summary>Reads an OBJ file.</summary>
    /// <param name="path">Where it is.</param>
    /// <param name="file">Its name in messages (default <paramref name="path"/>).</param>
    /// <exception cref="SceneException">It is missing, unreadable or malformed; the message names the file and the line.</exception>
    public static TriangleMesh Read(string path, string? file = null)
    {
        file ??= path;
        FileStream stream;
        try
        {
            stream = new FileStream(path, FileMode.Open, FileAccess.Read, FileShare.Read, 1);
        }
        catch (Exception e) when (e is IOException or UnauthorizedAccessException or ArgumentException or NotSupportedException)
        {
            throw new SceneException(file, string.Empty, 0, 0, string.Empty, "cannot read this OBJ file: " + e.Message);
        }

        using (stream)
        {
            return Read(stream, file);
        }
    }

    /// <summary>Reads OBJ text from a stream.</summary>
    /// <param name="stream">The bytes (UTF-8 or ASCII).</param>
    /// <param name="file">Its name in messages.</param>
    /// <exception cref="SceneException">It is malformed; the message names the file and the line.</exception>
    public static TriangleMesh Read(Stream stream, string file)
    {
        if (stream is null)
        {
            throw new ArgumentNullException(nameof(stream));
        }

        var parser = new Parser(file);
        var buffer = new byte[1 << 20];
        var filled = 0;
        while (true)
        {
            int read;
            try
            {
                read = stream.Read(buffer, filled, buffer.Length - filled);
            }
            catch (IOException e)
            {
                throw new SceneException(file, string.Empty, parser.Line, 0, string.Empty, "cannot read this OBJ file: " + e.Message);
            }

            filled += read;
            var start = 0;
            while (true)
            {
                var end = Array.IndexOf(buffer, (byte)'\n', start, filled - start);
                if (end < 0)
                {
                    break;
                }

                parser.ParseLine(new Span<byte>(buffer, start, end - start));
                start = end + 1;
            }

            if (read == 0)
            {
                if (start < filled)
                {
                    parser.ParseLine(new Span<byte>(buffer, start, filled - start));
                }

                break;
            }

            // Keep the unfinished line at the front; grow the buffer only for a line longer than it.
            var rest = filled - start;
            if (rest == buffer.Length)
            {
                if (buffer.Length >= MaxLineBytes)
                {
                    throw new SceneException(file, string.Empty, parser.Line + 1, 0, string.Empty, FormattableString.Invariant($"a line longer than {MaxLineBytes:N0} bytes"));
                }

                Array.Resize(ref buffer, 2 * buffer.Length);
            }
            else
            {
                Buffer.BlockCopy(buffer, start, buffer, 0, rest);
            }

            filled = rest;
        }

        return parser.Finish();
    }

    private sealed class Parser
    {
        private readonly string _file;
        private double[] _vertices = new double[3 * 1024];
        private int[] _triangles = new int[3 * 1024];
        private int _vertexCount;
        private int _triangleCount;
        private int[] _face = new int[16];
        private int[] _faceLines = new int[1024]; // the line of each triangle, for an index found bad at the end

        public Parser(string file)
        {
            _file = file;
        }

        public int Line { get; private set; }

        public void ParseLine(Span<byte> line)
        {
            Line++;
            var i = SkipSpace(line, 0);
            if (i == line.Length || line[i] == '#')
            {
                return;
            }

            var wordStart = i;
            while (i < line.Length && !IsSpace(line[i]))
            {
                i++;
            }

            var word = line.Slice(wordStart, i - wordStart);
            if (word.Length == 1 && word[0] == 'v')
            {
                Vertex(line, i);
            }
            else if (word.Length == 1 && word[0] == 'f')
            {
                Face(line, i);
            }
            else if (!IsIgnored(word))
            {
                throw Error(wordStart, $"'{Text(word)}' is not a statement this reader takes: v and f are read; vt, vn, o, g, s, usemtl, mtllib and # comments are ignored");
            }
        }

        public TriangleMesh Finish()
        {
            // A positive index may name a vertex defined later in the file: checked once all are known.
            for (var t = 0; t < 3 * _triangleCount; t++)
            {
                if (_triangles[t] >= _vertexCount)
                {
                    throw new SceneException(_file, string.Empty, _faceLines[t / 3], 0, string.Empty,
                        Invariant($"a face names vertex {_triangles[t] + 1}, and the file defines {_vertexCount}"));
                }
            }

            var vertices = new double[3 * _vertexCount];
            Array.Copy(_vertices, vertices, vertices.Length);
            var triangles = new int[3 * _triangleCount];
            Array.Copy(_triangles, triangles, triangles.Length);
            return new TriangleMesh(vertices, triangles);
        }

        private void Vertex(Span<byte> line, int i)
        {
            if (_vertexCount == MaxVertices)
            {
                throw Error(-1, Invariant($"more than {MaxVertices:N0} vertices"));
            }

            if (3 * (_vertexCount + 1) > _vertices.Length)
            {
                Array.Resize(ref _vertices, Math.Min(3 * MaxVertices, 2 * _vertices.Length));
            }

            var o = 3 * _vertexCount;
            var numbers = 0;
            while (true)
            {
                i = SkipSpace(line, i);
                if (i == line.Length)
                {
                    break;
                }

                var start = i;
                while (i < line.Length && !IsSpace(line[i]))
                {
                    i++;
                }

                var token = line.Slice(start, i - start);
                if (!DecimalParser.TryParse(token, out var value))
                {
                    throw Error(start, $"'{Text(token)}' is not a finite number; a vertex is v x y z");
                }

                if (numbers < 3)
                {
                    _vertices[o + numbers] = value;
                }

                numbers++;
            }

            if (numbers is not (3 or 4 or 6 or 7))
            {
                throw Error(-1, Invariant($"a vertex has {numbers} numbers; v takes x y z (and an optional w, or r g b)"));
            }

            _vertexCount++;
        }

        private void Face(Span<byte> line, int i)
        {
            var corners = 0;
            while (true)
            {
                i = SkipSpace(line, i);
                if (i == line.Length)
                {
                    break;
                }

                var start = i;
                while (i < line.Length && !IsSpace(line[i]))
                {
                    i++;
                }

                var token = line.Slice(start, i - start);
                var slash = token.IndexOf((byte)'/');
                var index = slash < 0 ? token : token.Slice(0, slash);
                if (!Utf8Parser.TryParse(index, out int v, out var used) || used != index.Length || v == 0)
                {
                    throw Error(start, $"'{Text(token)}' is not a vertex reference; a face corner is v, v/vt, v//vn or v/vt/vn with v from 1 (or negative, counted back)");
                }

                if (v < 0)
                {
                    if (-(long)v > _vertexCount)
                    {
                        throw Error(start, Invariant($"vertex {v} counts back past the first vertex: {_vertexCount} are defined before this line"));
                    }

                    v = _vertexCount + v;
                }
                else
                {
                    v--;
                }

                if (corners == _face.Length)
                {
                    Array.Resize(ref _face, 2 * _face.Length);
                }

                _face[corners++] = v;
            }

            if (corners < 3)
            {
                throw Error(-1, Invariant($"a face has {corners} vertices; it needs at least 3"));
            }

            for (var k = 1; k + 1 < corners; k++)
            {
                if (_triangleCount == MaxTriangles)
                {
                    throw Error(-1, Invariant($"more than {MaxTriangles:N0} triangles"));
                }

                if (3 * (_triangleCount + 1) > _triangles.Length)
                {
                    Array.Resize(ref _triangles, Math.Min(3 * MaxTriangles, 2 * _triangles.Length));
                }

                if (_triangleCount == _faceLines.Length)
                {
                    Array.Resize(ref _faceLines, Math.Min(MaxTriangles, 2 * _faceLines.Length));
                }

                var o = 3 * _triangleCount;
                _triangles[o] = _face[0];
                _triangles[o + 1] = _face[k];
                _triangles[o + 2] = _face[k + 1];
                _faceLines[_triangleCount] = Line;
                _triangleCount++;
            }
        }

        private static bool IsIgnored(Span<byte> word) =>
            Is(word, "vt") || Is(word, "vn") || Is(word, "o") || Is(word, "g") || Is(word, "s") || Is(word, "usemtl") || Is(word, "mtllib");

        private static bool Is(Span<byte> word, string name)
        {
            if (word.Length != name.Length)
            {
                return false;
            }

            for (var k = 0; k < word.Length; k++)
            {
                if (word[k] != name[k])
                {
                    return false;
                }
            }

            return true;
        }

        private static int SkipSpace(Span<byte> line, int i)
        {
            while (i < line.Length && IsSpace(line[i]))
            {
                i++;
            }

            return i;
        }

        private static bool IsSpace(byte b) => b is (byte)' ' or (byte)'\t' or (byte)'\r' or (byte)'\f' or (byte)'\v';

        private static string Text(Span<byte> bytes)
        {
            var shown = bytes.Length > 40 ? bytes.Slice(0, 40) : bytes;
            return Encoding.UTF8.GetString(shown.ToArray()) + (bytes.Length > 40 ? "..." : string.Empty);
        }

        private static string Invariant(FormattableString text) => text.ToString(System.Globalization.CultureInfo.InvariantCulture);

        private SceneException Error(int column, string problem) =>
            new(_file, string.Empty, Line, column + 1, string.Empty, problem);
    }
}
