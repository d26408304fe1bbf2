using System;
using System.Diagnostics;
using System.Globalization;
using System.IO;

namespace ParticlePhysics.Demo.Running;

/// <summary>
/// A one-line progress indicator on stderr for long runs: silent for the first second, then redrawn with a carriage
/// return a few times a second, and erased at the end (also after a divergence or Ctrl-C). Only built when stderr is
/// a terminal, so pipes and files never receive it. Rows printed on the same terminal go through
/// <see cref="WriteAbove"/>, which lifts the line out of their way and puts it back.
/// </summary>
internal sealed class ProgressReporter
{
    private const long QuietMilliseconds = 1000;
    private const long RedrawMilliseconds = 200;
    private readonly TextWriter _error;
    private readonly string _label;
    private readonly Stopwatch _clock = Stopwatch.StartNew();
    private long _lastDraw = QuietMilliseconds - RedrawMilliseconds;
    private string? _text;
    private bool _drawn;

    public ProgressReporter(TextWriter error, string label)
    {
        _error = error;
        _label = label;
    }

    /// <summary>Notes that <paramref name="step"/> of <paramref name="steps"/> is done.</summary>
    public void Report(int step, int steps)
    {
        if ((step & 63) != 0 && step != steps)
        {
            return;
        }

        var now = _clock.ElapsedMilliseconds;
        if (now - _lastDraw < RedrawMilliseconds)
        {
            return;
        }

        _lastDraw = now;
        _text = string.Format(
            CultureInfo.InvariantCulture, "{0}: step {1} of {2} ({3:0}%), {4:0.0} s elapsed", _label, step, steps, 100.0 * step / steps, now / 1000.0);
        Draw();
    }

    /// <summary>Erases the line if it is drawn, runs <paramref name="write"/> (which prints on the same terminal), and draws it again.</summary>
    public void WriteAbove(Action write)
    {
        var shown = _drawn;
        Clear();
        write();
        if (shown)
        {
            Draw();
        }
    }

    /// <summary>Erases the indicator if it is drawn (and whatever the terminal echoed after it, such as ^C).</summary>
    public void Clear()
    {
        if (_drawn)
        {
            _error.Write("\r" + new string(' ', _text!.Length + 4) + "\r");
            _error.Flush();
            _drawn = false;
        }
    }

    private void Draw()
    {
        _error.Write("\r" + _text + " ");
        _error.Flush();
        _drawn = true;
    }
}
