using System;
using System.CommandLine;
using System.IO;
using System.Text;
using ParticlePhysics.Demo.Cli;

namespace ParticlePhysics.Demo;

/// <summary>
/// The demo's entry point. <see cref="Run"/> takes the arguments and the two writers, so tests run the whole
/// program in-process; <see cref="Main"/> only binds it to the console.
/// </summary>
internal static class Program
{
    private static int Main(string[] args)
    {
        // A buffered stdout: csv of a big cloth is megabytes, and Console.Out flushes every write.
        using var output = new StreamWriter(Console.OpenStandardOutput(), new UTF8Encoding(false), 1 << 16) { AutoFlush = false };
        try
        {
            return Run(args, output, Console.Error, errorIsTerminal: !Console.IsErrorRedirected);
        }
        finally
        {
            output.Flush();
        }
    }

    /// <summary>Runs the demo with <paramref name="args"/>; returns the exit code (0 ok, 2 bad command line, 3 diverged).</summary>
    /// <param name="args">The command line, without the program name.</param>
    /// <param name="output">Receives the results (stdout).</param>
    /// <param name="error">Receives the error line and, when <paramref name="errorIsTerminal"/>, the progress indicator.</param>
    /// <param name="errorIsTerminal">True when <paramref name="error"/> is a terminal.</param>
    internal static int Run(string[] args, TextWriter output, TextWriter error, bool errorIsTerminal = false)
    {
        var context = new DemoContext(output, error, errorIsTerminal);
        var root = DemoCommandLine.Build(context);
        try
        {
            var parse = root.Parse(args);
            if (parse.Errors.Count > 0)
            {
                return Fail(output, error, ParseErrors.Describe(parse, root));
            }

            return parse.Invoke(new InvocationConfiguration { Output = output, Error = error, EnableDefaultExceptionHandler = false });
        }
        catch (UsageException exception)
        {
            return Fail(output, error, exception.Message);
        }
        catch (ArgumentException exception)
        {
            // The core's checks (a value the demo's own checks let through): keep its first sentence, drop the parameter suffix.
            var message = exception.Message.Split('\n')[0];
            var suffix = message.IndexOf(" (Parameter '", StringComparison.Ordinal);
            return Fail(output, error, suffix >= 0 ? message[..suffix] : message);
        }
    }

    private static int Fail(TextWriter output, TextWriter error, string message)
    {
        output.Flush();
        error.WriteLine("error: " + message);
        return ExitCodes.Usage;
    }
}
