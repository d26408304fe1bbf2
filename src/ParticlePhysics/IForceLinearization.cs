using System;

namespace ParticlePhysics;

/// <summary>
/// A force whose linearisation can give its forces and its diagonal blocks in the same pass. An implicit step needs,
/// at the same state, the force f, the Jacobian J = a df/dx + b df/dv and J's diagonal blocks; done separately
/// (<see cref="IForceGenerator.AddForces"/>, <see cref="IForceJacobian.Linearize"/>,
/// <see cref="IForceJacobian.AddDiagonalBlocks"/>) a spring computes its direction and length twice and walks its
/// elements three times. <see cref="ILinearizableSystem.AccumulateForcesAndLinearize"/> calls this instead when a
/// generator offers it.
/// </summary>
/// <remarks>
/// The result must be exactly that of the three calls in that order, to the last bit: the same values added into the
/// same accumulators in the same order (the tests compare both ways bit for bit). A generator that does not implement
/// this interface is simply called three times.
/// </remarks>
public interface IForceLinearization : IForceJacobian
{
    /// <summary>
    /// Adds the forces at <paramref name="state"/> into <paramref name="forces"/>, stores J = a df/dx + b df/dv there
    /// for the products that follow, adds (df/dx) v into <paramref name="positionJacobianTimesVelocity"/> and J's
    /// diagonal blocks into <paramref name="diagonalBlocks"/>: <see cref="IForceGenerator.AddForces"/>,
    /// <see cref="IForceJacobian.Linearize"/> and <see cref="IForceJacobian.AddDiagonalBlocks"/> in one pass.
    /// </summary>
    /// <param name="state">The state to evaluate and linearise at.</param>
    /// <param name="positionScale">a, the scale of df/dx in J.</param>
    /// <param name="velocityScale">b, the scale of df/dv in J.</param>
    /// <param name="forces">The force accumulator, 3 values per particle.</param>
    /// <param name="positionJacobianTimesVelocity">Receives (df/dx) v added to what it holds, 3 values per particle.</param>
    /// <param name="diagonalBlocks">Receives J_ii added to what it holds, 9 values per particle (row-major).</param>
    void AddForcesAndLinearize(
        in ParticleState state,
        double positionScale,
        double velocityScale,
        Span<double> forces,
        Span<double> positionJacobianTimesVelocity,
        Span<double> diagonalBlocks);
}
