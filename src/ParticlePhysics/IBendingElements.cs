using System;

namespace ParticlePhysics;

/// <summary>
/// The elements of a quadratic bending energy (<c>Forces.QuadraticBending</c>) as a position-based solver reads them.
/// Element e has up to 6 particles (a triangle and its three neighbours' far corners) and up to 3 components (a
/// symmetric 2 x 2 curvature); component k of it is the linear combination c_k = sum_v b_kv x_v of its particles'
/// positions (a vector: the same weights for x, y and z), and its energy is s / 2 sum_k |c_k|^2. Read-only, as <see cref="ISpringElements"/> is for springs.
/// </summary>
public interface IBendingElements : IForceGenerator
{
    /// <summary>Changes whenever an element is added.</summary>
    int TopologyVersion { get; }

    /// <summary>Changes whenever an element's stiffness changes.</summary>
    int ParameterVersion { get; }

    /// <summary>The number of elements.</summary>
    int ElementCount { get; }

    /// <summary>
    /// Copies the elements: 6 particle slots each into <paramref name="particles"/> (-1 for an
    /// unused slot), 3 x 6 weights b_kv each into
    /// <paramref name="weights"/> (row k, column v; 0 where unused), and the stiffness s of each into
    /// <paramref name="stiffness"/>.
    /// </summary>
    void CopyElements(Span<int> particles, Span<double> weights, Span<double> stiffness);
}
