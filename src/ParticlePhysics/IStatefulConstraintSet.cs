namespace ParticlePhysics;

/// <summary>
/// A constraint set whose calls leave something a caller can read after the step (the impacts a
/// <see cref="Contacts.ContactSet"/> logged, the tensions of a <see cref="Constraints.RodNetwork"/>), so that a failed
/// step must put it back: the world brackets its steps with these calls, as it does an integrator's state
/// (<see cref="IStatefulIntegrator"/>).
/// </summary>
/// <remarks>
/// All or nothing: <see cref="ParticleWorld.Step"/> calls <see cref="BeginStep"/> on every such set before its stages,
/// then <see cref="CommitStep"/> once the step is committed or <see cref="DiscardStep"/> when any stage threw or the
/// end state failed its checks; <see cref="DiscardStep"/> restores what the set showed before <see cref="BeginStep"/>.
/// A <see cref="Driver.FixedTimestepDriver"/> frame of several steps is one bracket, so a failed frame restores the
/// sets with the world. A set used without a world (its stages called directly) is never bracketed and keeps what its
/// last call left. Neither call may allocate once the set has grown to its world.
/// </remarks>
public interface IStatefulConstraintSet : IConstraintSet
{
    /// <summary>A step (or a frame of steps) starts: keep aside what a failure must restore.</summary>
    void BeginStep();

    /// <summary>The step was committed: what the set's calls left is now what it shows.</summary>
    void CommitStep();

    /// <summary>The step failed: show again what was kept aside at <see cref="BeginStep"/>.</summary>
    void DiscardStep();
}
