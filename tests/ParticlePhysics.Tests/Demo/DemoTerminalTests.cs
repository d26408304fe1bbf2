using System;
using System.Diagnostics;
using System.IO;
using System.Linq;
using System.Text;
using System.Text.RegularExpressions;
using System.Threading;

namespace ParticlePhysics.Tests.Demo;

/// <summary>
/// The demo on a real terminal: util-linux's <c>script</c> runs the built demo on a pseudo-terminal, so that its
/// stdout and stderr are a terminal as in a shell, and passes on what the test types (Ctrl-C, which the terminal
/// turns into SIGINT). Rows must show while the run goes on, and Ctrl-C must erase the progress line, keep the rows
/// and exit with 130.
/// </summary>
public sealed partial class DemoTerminalTests
{
    private static readonly TimeSpan _patience = TimeSpan.FromSeconds(120);

    [TerminalFact]
    public void On_a_terminal_rows_show_as_they_are_computed_and_ctrl_c_ends_cleanly()
    {
        // A 32 x 32 cloth for 60 s, a row every 500 steps: tens of seconds of work, and 120 rows of 55 bytes, far
        // less than the demo's 64 KiB output buffer, so that a row seen before Ctrl-C was flushed as it came.
        using var demo = Terminal.Start("cloth", "--resolution", "1/31", "--duration", "60", "--every", "500");

        var seen = demo.WaitFor(screen => DataRows(screen).Length >= 5 && screen.Contains("cloth: step ", StringComparison.Ordinal));

        Assert.True(seen, "no rows and progress line on the terminal while the run went on:\n" + demo.Transcript);
        Assert.False(demo.HasExited, "the run ended before Ctrl-C");
        var rowsBefore = DataRows(Screen(demo.Transcript));
        demo.Type("\u0003");
        Assert.True(demo.WaitForExit(), "the demo did not stop after Ctrl-C:\n" + demo.Transcript);

        Assert.Equal(130, demo.ExitCode);
        var screen = Screen(demo.Transcript);
        var all = screen.Split('\n').Select(l => l.TrimEnd()).Where(l => l.Length > 0).ToArray();

        // A run this long says what it will cost before it starts (stderr, on the same terminal), then the table.
        Assert.StartsWith("note: cloth will take 60,000 steps", all[0], StringComparison.Ordinal);
        var lines = all[1..];
        Assert.DoesNotContain(lines, l => l.Contains("cloth: step ", StringComparison.Ordinal)); // the progress line is gone
        Assert.Equal("           t        min_y    max_speed       energy", lines[1]);
        var rowsAfter = DataRows(screen);
        Assert.True(rowsAfter.Length >= rowsBefore.Length, "rows were lost");
        Assert.Equal(rowsBefore.Select(Time), rowsAfter.Take(rowsBefore.Length).Select(Time));
        Assert.StartsWith("interrupted (Ctrl-C) at t = ", lines[^2], StringComparison.Ordinal);
        Assert.Matches(@"^interrupted by Ctrl-C at t = [0-9.]+ s \(step [0-9]+ of 60000\); the rows printed so far were kept\.$", lines[^1]);
    }

    // The table's data rows: four numbers, t first.
    private static string[] DataRows(string screen) =>
        screen.Split('\n').Select(l => l.Trim()).Where(l => DataRow().IsMatch(l)).ToArray();

    private static string Time(string row) => row.Split(' ', StringSplitOptions.RemoveEmptyEntries)[0];

    /// <summary>What a terminal shows after <paramref name="transcript"/>: escape sequences dropped, \r back to column 0.</summary>
    private static string Screen(string transcript)
    {
        var text = Escape().Replace(transcript, string.Empty);
        var lines = new System.Collections.Generic.List<StringBuilder> { new() };
        var column = 0;
        foreach (var c in text)
        {
            switch (c)
            {
                case '\r':
                    column = 0;
                    break;
                case '\n':
                    lines.Add(new StringBuilder());
                    column = 0;
                    break;
                default:
                    var line = lines[^1];
                    if (column < line.Length)
                    {
                        line[column] = c;
                    }
                    else
                    {
                        line.Append(c);
                    }

                    column++;
                    break;
            }
        }

        return string.Join('\n', lines);
    }

    [GeneratedRegex(@"^-?[0-9][0-9.E+-]*( +-?[0-9][0-9.E+-]*){3}$")]
    private static partial Regex DataRow();

    [GeneratedRegex(@"\x1b(\[[0-9;?]*[A-Za-z]|[=>])")]
    private static partial Regex Escape();

    /// <summary>The built demo under <c>script</c>: a pseudo-terminal whose output the test reads as it comes.</summary>
    private sealed class Terminal : IDisposable
    {
        private readonly Process _process;
        private readonly StringBuilder _transcript = new();
        private readonly Thread _reader;

        private Terminal(Process process)
        {
            _process = process;
            _reader = new Thread(Read) { IsBackground = true };
            _reader.Start();
        }

        public string Transcript
        {
            get
            {
                lock (_transcript)
                {
                    return _transcript.ToString();
                }
            }
        }

        public bool HasExited => _process.HasExited;

        public int ExitCode => _process.ExitCode;

        public static Terminal Start(params string[] args)
        {
            var dotnet = Environment.GetEnvironmentVariable("DOTNET_HOST_PATH") is { Length: > 0 } host ? host : "dotnet";
            var demo = Path.Combine(AppContext.BaseDirectory, "ParticlePhysics.Demo.dll");
            // Through coreutils' env --default-signal=INT, as an interactive shell starts a foreground job: a test run
            // started in the background of a non-interactive shell (nohup ... &) ignores SIGINT, a child inherits that,
            // and .NET never installs its Ctrl-C handler for a signal ignored at start, so the demo would not stop.
            var command = string.Join(' ', new[] { "env", "--default-signal=INT", dotnet, demo }.Concat(args).Select(Quote));
            var start = new ProcessStartInfo("script")
            {
                RedirectStandardInput = true,
                RedirectStandardOutput = true,
                RedirectStandardError = true,
                UseShellExecute = false,
            };
            foreach (var a in new[] { "--quiet", "--return", "--flush", "--command", command, "/dev/null" })
            {
                start.ArgumentList.Add(a);
            }

            start.Environment["TERM"] = "xterm";
            return new Terminal(Process.Start(start)!);
        }

        /// <summary>Waits until <paramref name="condition"/> holds for the screen so far (or the demo exits, or patience runs out).</summary>
        public bool WaitFor(Func<string, bool> condition)
        {
            var clock = Stopwatch.StartNew();
            while (clock.Elapsed < _patience)
            {
                if (condition(Screen(Transcript)))
                {
                    return true;
                }

                if (_process.HasExited)
                {
                    return false;
                }

                Thread.Sleep(50);
            }

            return false;
        }

        public void Type(string keys)
        {
            _process.StandardInput.Write(keys);
            _process.StandardInput.Flush();
        }

        public bool WaitForExit()
        {
            var exited = _process.WaitForExit(_patience);
            _reader.Join(TimeSpan.FromSeconds(10));
            return exited;
        }

        public void Dispose()
        {
            if (!_process.HasExited)
            {
                _process.Kill(entireProcessTree: true);
                _process.WaitForExit();
            }

            _process.Dispose();
        }

        private static string Quote(string word) => "'" + word.Replace("'", "'\\''", StringComparison.Ordinal) + "'";

        private void Read()
        {
            var buffer = new char[4096];
            int count;
            while ((count = _process.StandardOutput.Read(buffer, 0, buffer.Length)) > 0)
            {
                lock (_transcript)
                {
                    _transcript.Append(buffer, 0, count);
                }
            }
        }
    }
}

/// <summary>A fact that needs a pseudo-terminal: it runs where util-linux's <c>script</c> is (Linux), and is skipped elsewhere.</summary>
[AttributeUsage(AttributeTargets.Method)]
public sealed class TerminalFactAttribute : FactAttribute
{
    public TerminalFactAttribute()
    {
        var found = OperatingSystem.IsLinux()
            && (Environment.GetEnvironmentVariable("PATH") ?? string.Empty).Split(':').Any(folder => File.Exists(Path.Combine(folder, "script")));
        if (!found)
        {
            Skip = "needs util-linux's script (a pseudo-terminal), which Linux has";
        }
    }
}
