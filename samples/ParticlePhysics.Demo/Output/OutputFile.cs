using System;
using System.IO;

namespace ParticlePhysics.Demo.Output;

/// <summary>Writes a chart or a replay page; a path that cannot be written is a usage error naming the option and the path.</summary>
internal static class OutputFile
{
    /// <summary>Refuses, before a run starts, a path that is not valid, names a folder, or lies in a folder that does not exist.</summary>
    /// <param name="option">The option that named the file (<c>--plot</c>, <c>--animate</c>), for the message.</param>
    /// <param name="path">The path given.</param>
    public static void CheckWritable(string option, string path)
    {
        string full;
        try
        {
            full = Path.GetFullPath(path);
        }
        catch (Exception exception) when (exception is ArgumentException or NotSupportedException or PathTooLongException)
        {
            throw new UsageException($"{option} '{path}' is not a valid file path: {exception.Message}", exception);
        }

        if (Directory.Exists(full))
        {
            throw new UsageException($"{option} cannot write '{path}': it is a folder; give a file name.");
        }

        var folder = Path.GetDirectoryName(full);
        if (folder is not null && !Directory.Exists(folder))
        {
            throw new UsageException($"{option} cannot write '{path}': the folder '{folder}' does not exist.");
        }
    }

    /// <summary>Writes <paramref name="text"/> to <paramref name="path"/>.</summary>
    public static void Write(string option, string path, string text) => Write(option, path, stream =>
    {
        using var writer = new StreamWriter(stream);
        writer.Write(text);
    });

    /// <summary>Creates <paramref name="path"/> and lets <paramref name="write"/> fill it.</summary>
    public static void Write(string option, string path, Action<Stream> write)
    {
        try
        {
            using var stream = new FileStream(path, FileMode.Create, FileAccess.Write, FileShare.None, 1 << 16);
            write(stream);
        }
        catch (Exception exception) when (exception is IOException or UnauthorizedAccessException or ArgumentException or NotSupportedException)
        {
            throw new UsageException($"{option} cannot write '{path}': {exception.Message}", exception);
        }
    }
}
