using System;

namespace ParticlePhysics;

/// <summary>
/// The springs of a force generator as a position-based solver reads them: ends, stiffness k, rest length L and axial
/// damping c of each spring between two particles, and of each spring to a fixed anchor. Read-only: the generator
/// stays a plain force (it never sees time-stepping), and the solver (<c>Constraints.SpringProjection</c>) copies what
/// it needs when <see cref="TopologyVersion"/> or <see cref="ParameterVersion"/> changes.
/// </summary>
public interface ISpringElements : IForceGenerator
{
    /// <summary>Changes whenever a spring is added (its ends are new), so that a solver knows to rebuild its batches.</summary>
    int TopologyVersion { get; }

    /// <summary>Changes whenever a stiffness, rest length, damping or anchor changes.</summary>
    int ParameterVersion { get; }

    /// <summary>The number of springs between two particles.</summary>
    int PairCount { get; }

    /// <summary>The number of springs between a particle and a fixed anchor.</summary>
    int AnchoredCount { get; }

    /// <summary>
    /// Copies the springs between two particles: ends i and j, and (k, L, c) into <paramref name="parameters"/>,
    /// 3 values per spring; each span holds at least <see cref="PairCount"/> springs.
    /// </summary>
    void CopyPairs(Span<int> first, Span<int> second, Span<double> parameters);

    /// <summary>
    /// Copies the anchored springs: the particle, and (ax, ay, az, k, L, c) into <paramref name="parameters"/>,
    /// 6 values per spring; each span holds at least <see cref="AnchoredCount"/> springs.
    /// </summary>
    void CopyAnchored(Span<int> particle, Span<double> parameters);
}
