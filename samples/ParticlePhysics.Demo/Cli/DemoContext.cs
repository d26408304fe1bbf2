using System.IO;
using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Demo.Cli;

/// <summary>Where the demo writes, and whether stderr is a terminal (which alone allows a progress indicator).</summary>
internal sealed record DemoContext(TextWriter Output, TextWriter Error, bool ErrorIsTerminal)
{
    /// <summary>A progress indicator on stderr, or null when stderr is not a terminal.</summary>
    public ProgressReporter? Progress(string label) => ErrorIsTerminal ? new ProgressReporter(Error, label) : null;
}
