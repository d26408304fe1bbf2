using System;
using System.Collections.Generic;
using System.IO;

namespace ParticlePhysics.Demo.Output;

/// <summary>The <c>--format</c> names and their writers.</summary>
internal static class OutputFormat
{
    /// <summary>The default format.</summary>
    public const string Default = "table";

    /// <summary>The names <c>--format</c> accepts.</summary>
    public static IReadOnlyList<string> Names { get; } = new[] { "table", "csv", "json" };

    /// <summary>A writer of runs in <paramref name="format"/> to <paramref name="output"/>.</summary>
    public static IRunWriter CreateRunWriter(string format, TextWriter output) => format switch
    {
        "table" => new TableRunWriter(output),
        "csv" => new CsvRunWriter(output),
        "json" => new JsonRunWriter(output),
        _ => throw new ArgumentOutOfRangeException(nameof(format), format, "Unknown format."),
    };
}
