using System;

namespace ParticlePhysics;

/// <summary>
/// The triangles of a membrane force (<c>Forces.TriangleMembrane</c>) as a position-based solver reads them: corners,
/// rest shape and material of each triangle. Read-only, as <see cref="ISpringElements"/> is for springs: the force stays
/// a plain force, and the solver (<c>Constraints.MembraneProjection</c>) copies what it needs when
/// <see cref="TopologyVersion"/> or <see cref="ParameterVersion"/> changes.
/// </summary>
public interface IMembraneElements : IForceGenerator
{
    /// <summary>Changes whenever a triangle is added, so that a solver knows to rebuild its batches.</summary>
    int TopologyVersion { get; }

    /// <summary>Changes whenever a triangle's material changes.</summary>
    int ParameterVersion { get; }

    /// <summary>The number of triangles.</summary>
    int TriangleCount { get; }

    /// <summary>
    /// Copies the triangles: their three corners into <paramref name="corners"/> (3 values each), and into
    /// <paramref name="parameters"/> 8 values each: the inverse rest-edge matrix Dm^-1 = [[p, q], [r, s]] (p, q, r, s),
    /// the rest area A0 (m^2), Lame's mu and the plane-stress lambda (N/m), and the damping time tau = eta / Y (s).
    /// The deformation gradient is F = (x1 - x0) (p, q) + (x2 - x0) (r, s) (two columns, 3 x 2).
    /// </summary>
    void CopyTriangles(Span<int> corners, Span<double> parameters);
}
