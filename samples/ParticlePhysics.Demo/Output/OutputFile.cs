using System;
using System.IO;

namespace ParticlePhysics.Demo.Output;

/// <summary>
/// A file that an option names (<c>--plot</c>, <c>--animate</c>): checked before the run starts, written after it. A
/// path that cannot be written is a usage error (exit code 2) naming the option and the path, found before anything
/// is printed, not after a long run.
/// </summary>
internal static class OutputFile
{
    /// <summary>
    /// Refuses, before a run starts, a path that cannot be written: one that is not valid, names a folder (<c>/</c>
    /// included), lies in a folder that does not exist, names a read-only file, or that the system refuses to open
    /// for writing (no permission, a read-only file system). The last check opens the file as the write will, without
    /// truncating it, and removes it again if it did not exist.
    /// </summary>
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

        var existed = File.Exists(full);
        if (existed && (File.GetAttributes(full) & FileAttributes.ReadOnly) != 0)
        {
            throw new UsageException($"{option} cannot write '{path}': the file is read-only.");
        }

        try
        {
            using (new FileStream(full, FileMode.OpenOrCreate, FileAccess.Write, FileShare.ReadWrite | FileShare.Delete))
            {
            }
        }
        catch (Exception exception) when (exception is IOException or UnauthorizedAccessException or NotSupportedException)
        {
            throw new UsageException($"{option} cannot write '{path}': {exception.Message}", exception);
        }
        finally
        {
            if (!existed)
            {
                TryDelete(full);
            }
        }
    }

    /// <summary>
    /// Refuses a path whose extension names another format than the one written (an SVG chart into <c>plot.png</c>, a
    /// page into <c>page.svg</c>): a viewer would open it as what its name says and fail.
    /// </summary>
    /// <param name="option">The option that named the file.</param>
    /// <param name="path">The path given.</param>
    /// <param name="format">What is written, in words ("SVG").</param>
    /// <param name="extensions">The extensions that name it, lower case with the dot, the first one suggested.</param>
    public static void CheckExtension(string option, string path, string format, params string[] extensions)
    {
        var extension = Path.GetExtension(path);
        foreach (var allowed in extensions)
        {
            if (string.Equals(extension, allowed, StringComparison.OrdinalIgnoreCase))
            {
                return;
            }
        }

        var named = extension.Length == 0 ? "has no extension" : $"ends in '{extension}'";
        throw new UsageException(
            $"{option} writes {format}, and '{path}' {named}; give a name ending in {string.Join(" or ", extensions)} (such as '{Path.ChangeExtension(Path.GetFileName(path), extensions[0])}').");
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

    private static void TryDelete(string path)
    {
        try
        {
            File.Delete(path);
        }
        catch (Exception exception) when (exception is IOException or UnauthorizedAccessException)
        {
            // The probe's empty file stays; the run writes over it.
        }
    }
}
