using System;

namespace ParticlePhysics;

/// <summary>
/// A force Jacobian that also states its sparsity: the pairs of particles it couples and, after each
/// <see cref="IForceJacobian.Linearize"/>, the off-diagonal 3 x 3 blocks J_ij of those pairs. The implicit stepper's
/// multigrid preconditioner builds its coarse levels from them (the matrix-free products stay the force's own).
/// </summary>
/// <remarks>
/// Pair forces (springs, dampers) have J_ij = -S and J_ii = J_jj = +S for each element between i and j, so a
/// coupling is simply an element. A force that does not implement this interface still acts on the step exactly
/// (through its products); only the preconditioner does without its off-diagonal part, as it does without the
/// diagonal of a force that adds no diagonal blocks.
/// </remarks>
public interface IJacobianCouplings : IForceJacobian
{
    /// <summary>
    /// The number of couplings: pairs (i, j) of distinct particles whose block J_ij may be non-zero. It and the pairs
    /// change only when the force's topology does (elements added or removed).
    /// </summary>
    int CouplingCount { get; }

    /// <summary>Writes the pairs, <see cref="CouplingCount"/> values each: coupling c joins first[c] and second[c].</summary>
    void WriteCouplings(Span<int> first, Span<int> second);

    /// <summary>
    /// Adds the blocks of the last linearisation into a caller's block matrix (assembly by a local-to-global map):
    /// for each coupling c, J_ij (i = first, j = second) into the 3 x 3 block that starts at
    /// <c>destination[9 forwardBlock[c]]</c> when <c>forwardBlock[c] &gt;= 0</c>, and J_ji = J_ij^T into the one at
    /// <c>destination[9 backwardBlock[c]]</c> when <c>backwardBlock[c] &gt;= 0</c> (row-major; both may be the same
    /// block). Each index is tested on its own: a negative one skips its block only (the multigrid stores a symmetric
    /// pair's block once, and names only one of the two for most couplings).
    /// Each block receives its couplings in increasing order, and nothing outside the named blocks is written, so calls
    /// whose named blocks do not overlap may run at the same time (the preconditioner assembles in parallel that way).
    /// </summary>
    void AddCouplingBlocks(Span<double> destination, ReadOnlySpan<int> forwardBlock, ReadOnlySpan<int> backwardBlock);
}
