namespace ParticlePhysics.Internal;

/// <summary>
/// A constraint set that is a contact stage: the world's step profile (<see cref="StepProfile"/>) books the time of its
/// calls as contacts' rather than constraints', and asks it for what only it can see: the part of that time its broad
/// phase took, and how many pairs and contacts it handled.
/// </summary>
/// <remarks>
/// The world calls <see cref="BeginProfile"/> before a profiled step's stages and <see cref="EndProfile"/> after them,
/// whether the step commits or fails (a failed step's figures are dropped), so a set times itself only inside a
/// profiled step. Neither call may allocate, and a set's results must not depend on whether it is profiled.
/// </remarks>
internal interface IContactStage
{
    /// <summary>A profiled step starts: from now on, add up the broad phase's Stopwatch ticks, the pairs and the contacts.</summary>
    void BeginProfile();

    /// <summary>
    /// The profiled step's stages are over: the <see cref="System.Diagnostics.Stopwatch"/> ticks the broad phase took
    /// over every call since <see cref="BeginProfile"/>, the candidate pairs it listed and the contacts resolved; stop
    /// adding them up.
    /// </summary>
    void EndProfile(out long broadPhaseTicks, out int pairs, out int contacts);
}
