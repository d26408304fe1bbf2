using System;
using System.Globalization;
using System.IO;
using System.Linq;
using ParticlePhysics.Demo;

namespace ParticlePhysics.Tests.Demo;

/// <summary>Runs the demo in-process, as a user would from the command line, and captures both streams.</summary>
internal static class DemoProcess
{
    public static DemoResult Run(params string[] args)
    {
        using var output = new StringWriter(CultureInfo.InvariantCulture);
        using var error = new StringWriter(CultureInfo.InvariantCulture);
        var exitCode = Program.Run(args, output, error);
        return new DemoResult(exitCode, output.ToString(), error.ToString());
    }

    /// <summary>Runs the demo as if Ctrl-C had been pressed as it started: every run stops before its first step.</summary>
    public static DemoResult RunInterrupted(params string[] args)
    {
        using var output = new StringWriter(CultureInfo.InvariantCulture);
        using var error = new StringWriter(CultureInfo.InvariantCulture);
        using var interrupt = new System.Threading.CancellationTokenSource();
        interrupt.Cancel();
        var exitCode = Program.Run(args, output, error, cancellation: interrupt.Token);
        return new DemoResult(exitCode, output.ToString(), error.ToString());
    }

    /// <summary>Runs the demo with <see cref="CultureInfo.CurrentCulture"/> set to <paramref name="culture"/>, then restores it.</summary>
    public static DemoResult RunUnder(CultureInfo culture, params string[] args)
    {
        var saved = CultureInfo.CurrentCulture;
        var savedUi = CultureInfo.CurrentUICulture;
        try
        {
            CultureInfo.CurrentCulture = culture;
            CultureInfo.CurrentUICulture = culture;
            return Run(args);
        }
        finally
        {
            CultureInfo.CurrentCulture = saved;
            CultureInfo.CurrentUICulture = savedUi;
        }
    }
}

internal sealed record DemoResult(int ExitCode, string Output, string Error)
{
    public string[] OutputLines => Output.Split('\n', StringSplitOptions.RemoveEmptyEntries).Select(l => l.TrimEnd('\r')).ToArray();

    public string[] ErrorLines => Error.Split('\n', StringSplitOptions.RemoveEmptyEntries).Select(l => l.TrimEnd('\r')).ToArray();

    /// <summary>The csv output: its header and its rows of numbers (parsed in the invariant culture).</summary>
    public (string[] Header, double[][] Rows) Csv()
    {
        var lines = OutputLines;
        var header = lines[0].Split(',');
        var rows = lines.Skip(1)
            .Select(l => l.Split(',').Select(v => double.Parse(v, NumberStyles.Float, CultureInfo.InvariantCulture)).ToArray())
            .ToArray();
        return (header, rows);
    }
}
