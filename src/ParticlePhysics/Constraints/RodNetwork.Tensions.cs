using System;

namespace ParticlePhysics.Constraints;

// The tensions the last evaluation found, and the all-or-nothing bracket that puts them back after a failed step.
public sealed partial class RodNetwork
{
    private double[] _tension = Array.Empty<double>();
    private double[] _savedTension = Array.Empty<double>(); // the tensions as they were before a step (BeginStep)
    private int _savedTensionCount;

    /// <summary>
    /// The tension of a link at the last evaluation of the constraint forces, in newtons (positive when it pulls its
    /// ends together; 0 for a slack cable, and before any evaluation).
    /// </summary>
    public double GetTension(int link)
    {
        CheckLink(link);
        return link < _tension.Length ? _tension[link] : 0.0;
    }

    /// <inheritdoc />
    /// <remarks>Keeps the tensions aside (<see cref="GetTension"/> is the last evaluation's, which a failed step ran).</remarks>
    public void BeginStep()
    {
        if (_savedTension.Length < _tension.Length)
        {
            _savedTension = new double[_tension.Length];
        }

        _savedTensionCount = _tension.Length;
        _tension.AsSpan().CopyTo(_savedTension);
    }

    /// <inheritdoc />
    public void CommitStep()
    {
    }

    /// <inheritdoc />
    /// <remarks>
    /// The tensions are those before the step again; links that the step's first evaluation sized for show 0, as
    /// they did before any evaluation.
    /// </remarks>
    public void DiscardStep()
    {
        var kept = Math.Min(_savedTensionCount, _tension.Length);
        _savedTension.AsSpan(0, kept).CopyTo(_tension);
        _tension.AsSpan(kept).Clear();
    }
}
