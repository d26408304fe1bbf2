using System;

namespace ParticlePhysics;

/// <summary>
/// An integrator that carries state from one step to the next (the adaptive <see cref="Integrators.DormandPrince45"/> carries its
/// internal step size, <see cref="Integrators.ImplicitEuler"/> its warm start), so that a snapshot can save it and a restored
/// run continues bit for bit as the original would. Integrators whose steps depend on nothing but their arguments need
/// not implement it.
/// </summary>
/// <remarks>
/// <para>
/// The state is a short list of doubles, so that it fits the snapshot's binary format without a serializer. Counters
/// and scratch buffers that do not change the next step's result are not state.
/// </para>
/// <para>
/// All or nothing: <see cref="IIntegrator.Step"/> never changes the state; it computes the state that would follow
/// and keeps it aside. The caller that accepts the step (<see cref="ParticleWorld.Step"/> and
/// <see cref="OdeSimulation.Step"/>, once their checks have passed and the new state is committed) calls
/// <see cref="CommitStep"/>; a caller that rejects it calls <see cref="DiscardStep"/>, and a step that throws is never
/// committed. So after a rejected or failed step the integrator is exactly as it was, and a retry takes the same step
/// as one taken after restoring a snapshot of the last good state. A caller that steps an integrator itself commits
/// the steps it keeps; one that never commits gets a correct integrator that forgets its state (a cold start at every
/// step).
/// </para>
/// </remarks>
public interface IStatefulIntegrator : IIntegrator
{
    /// <summary>
    /// The number of doubles that <see cref="WriteState"/> writes now. Fixed for some integrators (the adaptive step
    /// size of <see cref="Integrators.DormandPrince45"/>); for others it follows the system they last stepped (the warm start
    /// of <see cref="Integrators.ImplicitEuler"/>, 3 values per particle).
    /// </summary>
    int StateLength { get; }

    /// <summary>Writes the state (as of the last committed step) into <paramref name="destination"/> (exactly <see cref="StateLength"/> values).</summary>
    void WriteState(Span<double> destination);

    /// <summary>
    /// Replaces the state with <paramref name="source"/>, as some integrator of this type wrote it (its length need not
    /// be the current <see cref="StateLength"/>), and forgets any step not yet committed. Checks the length and every
    /// value first: a rejected call throws <see cref="ArgumentException"/> and changes nothing.
    /// </summary>
    void ReadState(ReadOnlySpan<double> source);

    /// <summary>
    /// The caller accepted the result of the last <see cref="IIntegrator.Step"/>: the state that step computed becomes
    /// the integrator's state. Does nothing when no step is waiting (none taken since the last commit or discard).
    /// </summary>
    void CommitStep();

    /// <summary>The caller rejected the result of the last <see cref="IIntegrator.Step"/>: forget the state it computed.</summary>
    void DiscardStep();
}
