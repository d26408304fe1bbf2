using System.IO;
using System.Threading;
using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Demo.Cli;

/// <summary>
/// Where the demo writes, whether each stream is a terminal (stderr: a progress indicator is allowed; stdout: rows
/// are flushed as they come), and the token that Ctrl-C cancels.
/// </summary>
internal sealed record DemoContext(TextWriter Output, TextWriter Error, bool ErrorIsTerminal, bool OutputIsTerminal = false, CancellationToken Cancellation = default)
{
    /// <summary>A progress indicator on stderr, or null when stderr is not a terminal.</summary>
    public ProgressReporter? Progress(string label) => ErrorIsTerminal ? new ProgressReporter(Error, label) : null;
}
