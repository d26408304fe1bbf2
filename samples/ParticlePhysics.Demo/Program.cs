using System;
using System.CommandLine;
using System.Globalization;
using System.IO;
using System.Text;
using System.Threading;
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
        // A buffered stdout: csv of a big cloth is megabytes, and Console.Out flushes every write. On a terminal the
        // scenario command flushes after each row, so that rows show as they are computed.
        using var output = new StreamWriter(Console.OpenStandardOutput(), new UTF8Encoding(false), 1 << 16) { AutoFlush = false };

        // The first Ctrl-C asks the run to stop after its current step (the rows so far are kept, exit code 130);
        // a second one, while the demo is still finishing, ends the process at once.
        using var interrupt = new CancellationTokenSource();
        Console.CancelKeyPress += (_, e) =>
        {
            if (!interrupt.IsCancellationRequested)
            {
                e.Cancel = true;
                interrupt.Cancel();
            }
        };
        try
        {
            return Run(args, output, Console.Error, !Console.IsErrorRedirected, !Console.IsOutputRedirected, interrupt.Token);
        }
        finally
        {
            output.Flush();
        }
    }

    /// <summary>Runs the demo with <paramref name="args"/>; returns the exit code (0 ok, 2 bad command line, 3 diverged, 130 interrupted).</summary>
    /// <param name="args">The command line, without the program name.</param>
    /// <param name="output">Receives the results (stdout).</param>
    /// <param name="error">Receives the error line and, when <paramref name="errorIsTerminal"/>, the progress indicator.</param>
    /// <param name="errorIsTerminal">True when <paramref name="error"/> is a terminal.</param>
    /// <param name="outputIsTerminal">True when <paramref name="output"/> is a terminal: rows are flushed one by one.</param>
    /// <param name="cancellation">Ctrl-C: stops a run between two steps, keeping the rows so far (exit code 130).</param>
    internal static int Run(
        string[] args, TextWriter output, TextWriter error, bool errorIsTerminal = false, bool outputIsTerminal = false, CancellationToken cancellation = default)
    {
        var context = new DemoContext(output, error, errorIsTerminal, outputIsTerminal, cancellation);
        var root = DemoCommandLine.Build(context);

        // One language and one number format whatever the machine's locale: System.CommandLine's own messages (a
        // missing value, the help's headings) follow the UI culture, and the help's defaults the culture (0,01 under
        // fr_FR, which the parser, invariant as the contract says, would then refuse).
        var (culture, uiCulture) = (CultureInfo.CurrentCulture, CultureInfo.CurrentUICulture);
        CultureInfo.CurrentCulture = CultureInfo.InvariantCulture;
        CultureInfo.CurrentUICulture = CultureInfo.InvariantCulture;
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
        catch (Scenes.SceneException exception)
        {
            // A scene file that cannot be used: its one line names the file, the JSON path, the line and the column.
            return Fail(output, error, exception.Message);
        }
        catch (ArgumentException exception)
        {
            // The core's checks (a value the demo's own checks let through): keep its first sentence, drop the parameter suffix.
            var message = exception.Message.Split('\n')[0];
            var suffix = message.IndexOf(" (Parameter '", StringComparison.Ordinal);
            return Fail(output, error, suffix >= 0 ? message[..suffix] : message);
        }
        finally
        {
            CultureInfo.CurrentCulture = culture;
            CultureInfo.CurrentUICulture = uiCulture;
        }
    }

    private static int Fail(TextWriter output, TextWriter error, string message)
    {
        output.Flush();
        error.WriteLine("error: " + message);
        return ExitCodes.Usage;
    }
}
