using System;
using System.Text;

namespace ParticlePhysics.Scenes;

/// <summary>
/// A scene file (or an OBJ file it names) that cannot be used: the one exception the loader lets out. Its
/// <see cref="Exception.Message"/> is one line that names the file, the JSON path of the offending value
/// (<c>objects[2].stiffness</c>), its line and column where they are known, the value, and what is allowed:
/// <c>cradle.json:14:20: objects[1].stiffness = -5: must be a finite number &gt;= 0 (N/m)</c>.
/// </summary>
public sealed class SceneException : Exception
{
    /// <summary>Creates the error; <paramref name="line"/> and <paramref name="column"/> are 1-based, 0 when unknown.</summary>
    /// <param name="file">The file, as the user named it.</param>
    /// <param name="path">The JSON path of the value (<c>objects[2].pairs[0][1]</c>), empty for the whole file.</param>
    /// <param name="line">The value's line, from 1; 0 when unknown.</param>
    /// <param name="column">The value's column, from 1; 0 when unknown.</param>
    /// <param name="value">The offending value as the file writes it (or a short description), empty when none.</param>
    /// <param name="problem">What is wrong and what is allowed.</param>
    public SceneException(string file, string path, int line, int column, string value, string problem)
        : base(Format(file, path, line, column, value, problem))
    {
        File = file;
        JsonPath = path;
        Line = line;
        Column = column;
        Value = value;
        Problem = problem;
    }

    /// <summary>Not for use: a scene error always names its file and problem.</summary>
    public SceneException()
        : this(string.Empty, string.Empty, 0, 0, string.Empty, "invalid scene")
    {
    }

    /// <summary>Not for use: a scene error always names its file and problem.</summary>
    public SceneException(string message)
        : this(string.Empty, string.Empty, 0, 0, string.Empty, message)
    {
    }

    /// <summary>Not for use: a scene error always names its file and problem.</summary>
    public SceneException(string message, Exception innerException)
        : base(message, innerException)
    {
        File = string.Empty;
        JsonPath = string.Empty;
        Value = string.Empty;
        Problem = message;
    }

    /// <summary>The file, as the user named it.</summary>
    public string File { get; }

    /// <summary>The JSON path of the offending value, empty for the file as a whole.</summary>
    public string JsonPath { get; }

    /// <summary>The line of the value, from 1 (0: unknown).</summary>
    public int Line { get; }

    /// <summary>The column of the value, from 1 (0: unknown).</summary>
    public int Column { get; }

    /// <summary>The offending value as written, or empty.</summary>
    public string Value { get; }

    /// <summary>What is wrong, and what is allowed.</summary>
    public string Problem { get; }

    private static string Format(string file, string path, int line, int column, string value, string problem)
    {
        var text = new StringBuilder();
        text.Append(file);
        if (line > 0)
        {
            text.Append(':').Append(line);
            if (column > 0)
            {
                text.Append(':').Append(column);
            }
        }

        text.Append(": ");
        if (path.Length > 0)
        {
            text.Append(path);
            text.Append(value.Length > 0 ? " = " + value : string.Empty);
            text.Append(": ");
        }
        else if (value.Length > 0)
        {
            text.Append(value).Append(": ");
        }

        text.Append(problem);

        // One line whatever the file held: a value or a key with a line break in it is shown escaped.
        return text.ToString().Replace("\r", "\\r").Replace("\n", "\\n");
    }
}
