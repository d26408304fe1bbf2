using System;

namespace ParticlePhysics;

/// <summary>
/// An integrator that carries state from one step to the next (the adaptive <see cref="Integrators.DormandPrince45"/> carries its
/// internal step size), so that a snapshot can save it and a restored run continues bit for bit as the original would.
/// Integrators whose steps depend on nothing but their arguments need not implement it.
/// </summary>
/// <remarks>
/// The state is a short list of doubles, so that it fits the snapshot's binary format without a serializer. Counters
/// and scratch buffers that do not change the next step's result are not state.
/// </remarks>
public interface IStatefulIntegrator : IIntegrator
{
    /// <summary>
    /// The number of doubles that <see cref="WriteState"/> writes now. Fixed for some integrators (the adaptive step
    /// size of <see cref="Integrators.DormandPrince45"/>); for others it follows the system they last stepped (the warm start
    /// of <see cref="Integrators.ImplicitEuler"/>, 3 values per particle).
    /// </summary>
    int StateLength { get; }

    /// <summary>Writes the state into <paramref name="destination"/> (exactly <see cref="StateLength"/> values).</summary>
    void WriteState(Span<double> destination);

    /// <summary>
    /// Replaces the state with <paramref name="source"/>, as some integrator of this type wrote it (its length need not
    /// be the current <see cref="StateLength"/>). Checks the length and every value first: a rejected call throws
    /// <see cref="ArgumentException"/> and changes nothing.
    /// </summary>
    void ReadState(ReadOnlySpan<double> source);
}
