using System;

namespace ParticlePhysics.Contacts;

/// <summary>
/// What the broad phase between particles reads of each particle: an axis-aligned box (3 minima and 3 maxima per
/// particle), the distance its centre may sweep within the interval, and, inside substeps, whether it moved its radius
/// or more (<see cref="Fast"/>). Filled anew by each step or substep; the arrays grow with the particle count only.
/// </summary>
internal sealed class ParticleBoxes
{
    /// <summary>The boxes' lower corners, x, y, z per particle.</summary>
    public double[] Min { get; private set; } = Array.Empty<double>();

    /// <summary>The boxes' upper corners, x, y, z per particle.</summary>
    public double[] Max { get; private set; } = Array.Empty<double>();

    /// <summary>How far each centre may move from its start within the step: the chord plus the path's bulge, in m.</summary>
    public double[] Sweep { get; private set; } = Array.Empty<double>();

    /// <summary>Inside substeps: whether each particle moved its radius or more (its pairs are then swept).</summary>
    public bool[] Fast { get; private set; } = Array.Empty<bool>();

    /// <summary>Makes room for <paramref name="count"/> particles.</summary>
    public void EnsureCapacity(int count)
    {
        if (Sweep.Length < count)
        {
            Min = new double[3 * count];
            Max = new double[3 * count];
            Sweep = new double[count];
            Fast = new bool[count];
        }
    }
}
