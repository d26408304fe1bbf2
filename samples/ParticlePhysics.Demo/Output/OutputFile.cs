using System;
using System.IO;

namespace ParticlePhysics.Demo.Plotting;

/// <summary>Writes a chart; a path that cannot be written is a usage error naming the path.</summary>
internal static class PlotFile
{
    /// <summary>Refuses, before a run starts, a path whose folder does not exist.</summary>
    public static void CheckWritable(string path)
    {
        string? folder;
        try
        {
            folder = Path.GetDirectoryName(Path.GetFullPath(path));
        }
        catch (Exception exception) when (exception is ArgumentException or NotSupportedException or PathTooLongException)
        {
            throw new UsageException($"--plot '{path}' is not a valid file path: {exception.Message}", exception);
        }

        if (folder is not null && !Directory.Exists(folder))
        {
            throw new UsageException($"--plot cannot write '{path}': the folder '{folder}' does not exist.");
        }
    }

    /// <summary>Writes the SVG document to <paramref name="path"/>.</summary>
    public static void Write(string path, string svg)
    {
        try
        {
            File.WriteAllText(path, svg);
        }
        catch (Exception exception) when (exception is IOException or UnauthorizedAccessException or ArgumentException or NotSupportedException)
        {
            throw new UsageException($"--plot cannot write '{path}': {exception.Message}", exception);
        }
    }
}
