using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Demo.Plotting;

/// <summary>A chart of one run: it sees the output rows as they come and draws itself at the end.</summary>
internal interface IRunPlot
{
    /// <summary>True for the steps whose rows the chart needs (the runner hands them over even off the output stride).</summary>
    bool Wants(int step);

    /// <summary>Sees one row (the array is reused by the runner: copy what you keep).</summary>
    void Add(double[] row);

    /// <summary>The SVG document.</summary>
    string ToSvg(RunOutcome outcome);
}
