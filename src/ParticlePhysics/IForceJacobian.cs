using System;

namespace ParticlePhysics;

/// <summary>
/// A force generator that can linearise itself for an implicit step. Once per step the implicit integrator calls
/// <see cref="Linearize"/> at the current state with two scales a and b; every later product then uses the
/// combined Jacobian J = a df/dx + b df/dv evaluated at that state, so that the (many) products of a
/// conjugate-gradient solve cost no square roots and no divisions.
/// </summary>
/// <remarks>
/// The Jacobian must be symmetric and negative semi-definite (forces that resist displacement and relative
/// velocity), so that the implicit system M - J stays symmetric positive definite. Springs clamp the transverse
/// stiffness of a compressed spring to zero for that reason, and drop the position derivative of axial damping,
/// which is not symmetric (it vanishes when the ends move together).
/// </remarks>
public interface IForceJacobian
{
    /// <summary>
    /// Stores J = <paramref name="positionScale"/> df/dx + <paramref name="velocityScale"/> df/dv at
    /// <paramref name="state"/> for the products that follow, and adds (df/dx) v, with v the state's velocities,
    /// into <paramref name="positionJacobianTimesVelocity"/> (3 values per particle).
    /// </summary>
    void Linearize(
        in ParticleState state, double positionScale, double velocityScale, Span<double> positionJacobianTimesVelocity);

    /// <summary>Adds J w into <paramref name="result"/> (3 values per particle each).</summary>
    void AddJacobianProduct(ReadOnlySpan<double> w, Span<double> result);

    /// <summary>Adds the diagonal 3 x 3 blocks J_ii into <paramref name="blocks"/> (9 values per particle, row-major).</summary>
    void AddDiagonalBlocks(Span<double> blocks);
}
