namespace ParticlePhysics.Internal;

/// <summary>
/// A linearisable system that can tell, without writing its couplings out, that they have not changed: the implicit
/// stepper's multigrid otherwise compares them pair by pair at every step to know whether to rebuild its aggregates,
/// two arrays of one int per coupling written and compared on the calling thread while the other threads wait.
/// </summary>
internal interface ICouplingRevision
{
    /// <summary>
    /// True when every force that states couplings only ever appends them (<see cref="IAppendOnlyCouplings"/>), with
    /// <paramref name="revision"/> a number that no other system gives and that changes whenever this system's set of
    /// forces does: then the couplings are the same as long as the revision and
    /// <see cref="ILinearizableSystem.CouplingCount"/> are, even for a solver that steps several systems in turn. False
    /// when some force's couplings may change in place (a user's <see cref="IJacobianCouplings"/>): compare them.
    /// </summary>
    bool TryGetCouplingRevision(out long revision);
}
