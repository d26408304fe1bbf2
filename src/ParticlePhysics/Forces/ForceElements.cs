using System;

namespace ParticlePhysics.Forces;

/// <summary>
/// The storage behind the spring and damper networks: elements that each join a particle to another particle
/// (or to a fixed anchor), with a fixed number of double parameters per element, in flat arrays that the hot
/// loops read directly (structure of arrays, no object per element).
/// </summary>
internal sealed class ForceElements
{
    private readonly int _stride;

    public ForceElements(int parametersPerElement)
    {
        _stride = parametersPerElement;
    }

    /// <summary>The number of elements.</summary>
    public int Count { get; private set; }

    /// <summary>The first particle of each element.</summary>
    public int[] First { get; private set; } = Array.Empty<int>();

    /// <summary>The second particle of each element (unused for anchored elements).</summary>
    public int[] Second { get; private set; } = Array.Empty<int>();

    /// <summary>The parameters, <c>parametersPerElement</c> consecutive values per element.</summary>
    public double[] Parameters { get; private set; } = Array.Empty<double>();

    /// <summary>The most elements one generator holds, so that every array (up to 6 parameters each) stays within .NET's array limit.</summary>
    public const int MaxElements = 256 * 1024 * 1024;

    public int Add(int first, int second, ReadOnlySpan<double> parameters)
    {
        if (Count == MaxElements)
        {
            throw new InvalidOperationException($"A force generator holds at most {MaxElements} elements; this one is full.");
        }

        if (Count == First.Length)
        {
            var capacity = (int)Math.Min(MaxElements, Math.Max(8L, 2L * Count));
            var firsts = First;
            var seconds = Second;
            var values = Parameters;
            Array.Resize(ref firsts, capacity);
            Array.Resize(ref seconds, capacity);
            Array.Resize(ref values, capacity * _stride);
            First = firsts;
            Second = seconds;
            Parameters = values;
        }

        First[Count] = first;
        Second[Count] = second;
        parameters.CopyTo(Parameters.AsSpan(Count * _stride, _stride));
        return Count++;
    }

    public void CheckIndex(int element, string name)
    {
        if ((uint)element >= (uint)Count)
        {
            throw new ArgumentOutOfRangeException(
                name, element, $"{name} must name an existing element, 0 to {Count - 1}; got {element}.");
        }
    }
}
