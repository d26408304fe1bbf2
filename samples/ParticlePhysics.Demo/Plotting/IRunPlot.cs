using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Demo.Plotting;

/// <summary>A chart of one run: it sees the rows it wants as they come and draws itself at the end.</summary>
internal interface IRunPlot : IRunObserver
{
    /// <summary>The SVG document, after <see cref="IRunObserver.Finish"/>.</summary>
    string ToSvg(RunOutcome outcome);
}
