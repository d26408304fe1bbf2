using System;

namespace ParticlePhysics.Contacts;

/// <summary>
/// The contacts the last position pass of a substep found (<see cref="ContactSet.Project"/>), for its velocity pass
/// (<see cref="ContactSet.SolveVelocities"/>): for each, an obstacle's index (or -1 for a pair), the particles, the
/// normal, the normal correction |C| and the normal velocity before the solve. Grows by doubling and is kept.
/// </summary>
internal sealed class SubstepContacts
{
    private int[] _kind = Array.Empty<int>();
    private int[] _first = Array.Empty<int>();
    private int[] _second = Array.Empty<int>();
    private Vector3d[] _normal = Array.Empty<Vector3d>();
    private double[] _depth = Array.Empty<double>();
    private double[] _approach = Array.Empty<double>();

    /// <summary>The number of contacts.</summary>
    public int Count { get; private set; }

    /// <summary>The end time of the substep they were found in.</summary>
    public double End { get; set; }

    /// <summary>Contact <paramref name="c"/>'s obstacle (its index), or -1 between two particles.</summary>
    public int Kind(int c) => _kind[c];

    /// <summary>Its particle (for a pair, the first).</summary>
    public int First(int c) => _first[c];

    /// <summary>For a pair, its second particle (-1 for an obstacle).</summary>
    public int Second(int c) => _second[c];

    /// <summary>Its normal (from the obstacle, or from the second particle to the first).</summary>
    public Vector3d Normal(int c) => _normal[c];

    /// <summary>Its normal correction |C|, in m.</summary>
    public double Depth(int c) => _depth[c];

    /// <summary>Its normal relative velocity before the solve (negative approaching), in m/s.</summary>
    public double Approach(int c) => _approach[c];

    /// <summary>Empties the list.</summary>
    public void Clear() => Count = 0;

    /// <summary>Appends a contact.</summary>
    public void Add(int kind, int first, int second, Vector3d normal, double depth, double approach)
    {
        if (Count == _kind.Length)
        {
            var capacity = Math.Max(64, 2 * _kind.Length);
            Array.Resize(ref _kind, capacity);
            Array.Resize(ref _first, capacity);
            Array.Resize(ref _second, capacity);
            Array.Resize(ref _normal, capacity);
            Array.Resize(ref _depth, capacity);
            Array.Resize(ref _approach, capacity);
        }

        _kind[Count] = kind;
        _first[Count] = first;
        _second[Count] = second;
        _normal[Count] = normal;
        _depth[Count] = depth;
        _approach[Count] = approach;
        Count++;
    }
}
