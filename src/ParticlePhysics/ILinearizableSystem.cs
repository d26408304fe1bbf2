using System;
using ParticlePhysics.Parallel;

namespace ParticlePhysics;

/// <summary>
/// What an implicit stepper needs of a mechanical system beyond its accelerations: the masses, the forces at a state,
/// and their linearisation there, J = a df/dx + b df/dv, as matrix-free products and 3 x 3 diagonal blocks.
/// <see cref="ParticleWorld"/> implements it over its force generators (and the constraint sets that act through forces
/// and linearise them: <see cref="IConstraintForces"/>), so that the stepper never sees forces.
/// </summary>
/// <remarks>
/// The stepper calls <see cref="Linearize"/> once per step, then any number of <see cref="AddJacobianProduct"/> and
/// <see cref="AddDiagonalBlocks"/> calls, which all use the J stored by that call. J must be symmetric and negative
/// semi-definite, so that M - J is symmetric positive definite (see <see cref="IForceJacobian"/>).
/// A preconditioner that handles the long wavelengths of a large system (multigrid) needs J's sparsity and values
/// as well: <see cref="CouplingCount"/>, <see cref="WriteCouplings"/> and <see cref="AddCouplingBlocks"/> give them,
/// for the forces that state theirs (<see cref="IJacobianCouplings"/>).
/// </remarks>
public interface ILinearizableSystem : ISecondOrderSystem
{
    /// <summary>The masses, one per particle (<see cref="ISecondOrderSystem.CoordinateCount"/> / 3 values).</summary>
    ReadOnlySpan<double> Masses { get; }

    /// <summary>The inverse masses, one per particle: 0 for an immovable (pinned) particle, whose velocity change is 0.</summary>
    ReadOnlySpan<double> InverseMasses { get; }

    /// <summary>The forces at (<paramref name="time"/>, x, v), 3 values per particle, valid until the next evaluation.</summary>
    ReadOnlySpan<double> AccumulateForces(double time, ReadOnlySpan<double> positions, ReadOnlySpan<double> velocities);

    /// <summary>
    /// Stores J = <paramref name="positionScale"/> df/dx + <paramref name="velocityScale"/> df/dv at (x, v) for the
    /// products that follow, and adds (df/dx) v into <paramref name="positionJacobianTimesVelocity"/>.
    /// </summary>
    /// <param name="time">The time of the linearisation.</param>
    /// <param name="positions">x, 3 values per particle.</param>
    /// <param name="velocities">v, 3 values per particle.</param>
    /// <param name="positionScale">a, the scale of df/dx in J.</param>
    /// <param name="velocityScale">b, the scale of df/dv in J.</param>
    /// <param name="userForces">How forces that supply no Jacobian of their own enter J.</param>
    /// <param name="positionJacobianTimesVelocity">Receives (df/dx) v added to what it holds, 3 values per particle.</param>
    void Linearize(
        double time,
        ReadOnlySpan<double> positions,
        ReadOnlySpan<double> velocities,
        double positionScale,
        double velocityScale,
        UserForceTreatment userForces,
        Span<double> positionJacobianTimesVelocity);

    /// <summary>
    /// <see cref="AccumulateForces"/>, <see cref="Linearize"/> and <see cref="AddDiagonalBlocks"/> at the same state in
    /// one call, with exactly their results: the forces at (x, v) are returned (valid until the next evaluation), J is
    /// stored for the products that follow, (df/dx) v is added into <paramref name="positionJacobianTimesVelocity"/>
    /// and J's diagonal blocks into <paramref name="diagonalBlocks"/>. What an implicit step needs first; a force that
    /// can do the three in one pass (<see cref="IForceLinearization"/>) does, and the others are called three times.
    /// </summary>
    /// <param name="time">The time of the evaluation and the linearisation.</param>
    /// <param name="positions">x, 3 values per particle.</param>
    /// <param name="velocities">v, 3 values per particle.</param>
    /// <param name="positionScale">a, the scale of df/dx in J.</param>
    /// <param name="velocityScale">b, the scale of df/dv in J.</param>
    /// <param name="userForces">How forces that supply no Jacobian of their own enter J.</param>
    /// <param name="positionJacobianTimesVelocity">Receives (df/dx) v added to what it holds, 3 values per particle.</param>
    /// <param name="diagonalBlocks">Receives J_ii added to what it holds, 9 values per particle (row-major).</param>
    /// <returns>The forces, 3 values per particle, as <see cref="AccumulateForces"/> returns them.</returns>
    ReadOnlySpan<double> AccumulateForcesAndLinearize(
        double time,
        ReadOnlySpan<double> positions,
        ReadOnlySpan<double> velocities,
        double positionScale,
        double velocityScale,
        UserForceTreatment userForces,
        Span<double> positionJacobianTimesVelocity,
        Span<double> diagonalBlocks);

    /// <summary>Adds J w into <paramref name="result"/> (3 values per particle each).</summary>
    void AddJacobianProduct(ReadOnlySpan<double> w, Span<double> result);

    /// <summary>Adds the diagonal 3 x 3 blocks J_ii into <paramref name="blocks"/> (9 values per particle, row-major).</summary>
    void AddDiagonalBlocks(Span<double> blocks);

    /// <summary>
    /// The off-diagonal couplings of the J stored by the last <see cref="Linearize"/>: pairs (i, j) of distinct
    /// particles, possibly repeated, whose block J_ij may be non-zero. Changes only when the topology does.
    /// </summary>
    int CouplingCount { get; }

    /// <summary>Writes the coupled pairs (<see cref="CouplingCount"/> values each), in a fixed order.</summary>
    void WriteCouplings(Span<int> first, Span<int> second);

    /// <summary>
    /// Adds the blocks J_ij and J_ji of the couplings into a caller's block matrix, as
    /// <see cref="IJacobianCouplings.AddCouplingBlocks"/> does, with one forward and one backward block index per
    /// coupling in the order of <see cref="WriteCouplings"/>.
    /// </summary>
    void AddCouplingBlocks(Span<double> destination, ReadOnlySpan<int> forwardBlock, ReadOnlySpan<int> backwardBlock);

    /// <summary>The runner over which the stepper may split its own passes, or null for the calling thread alone.</summary>
    IParallelRunner? Runner { get; }
}
