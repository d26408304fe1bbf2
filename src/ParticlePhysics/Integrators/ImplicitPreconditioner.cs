namespace ParticlePhysics.Integrators;

/// <summary>The preconditioner of <see cref="ImplicitEuler"/>'s conjugate gradients.</summary>
public enum ImplicitPreconditioner
{
    /// <summary>
    /// Aggregation multigrid over the couplings the forces state, added to block Jacobi (the default): the
    /// iterations no longer grow with the size of a stiff cloth.
    /// </summary>
    Multigrid,

    /// <summary>The inverse of each particle's 3 x 3 diagonal block of M - J alone: cheap per iteration, weak on long wavelengths.</summary>
    BlockJacobi,
}
