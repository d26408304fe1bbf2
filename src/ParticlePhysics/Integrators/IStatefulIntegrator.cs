using System;

namespace ParticlePhysics.Integrators;

/// <summary>
/// An integrator that carries state from one step to the next (the adaptive <see cref="DormandPrince45"/> carries its
/// internal step size), so that a snapshot can save it and a restored run continues bit for bit as the original would.
/// Integrators whose steps depend on nothing but their arguments need not implement it.
/// </summary>
/// <remarks>
/// The state is a short list of doubles, so that it fits the snapshot's binary format without a serializer. Counters
/// and scratch buffers that do not change the next step's result are not state.
/// </remarks>
public interface IStatefulIntegrator : IIntegrator
{
    /// <summary>The number of doubles in the state; fixed for a given integrator type.</summary>
    int StateLength { get; }

    /// <summary>Writes the state into <paramref name="destination"/> (exactly <see cref="StateLength"/> values).</summary>
    void WriteState(Span<double> destination);

    /// <summary>
    /// Replaces the state with <paramref name="source"/> (exactly <see cref="StateLength"/> values). Checks every
    /// value first: a rejected call throws <see cref="ArgumentException"/> and changes nothing.
    /// </summary>
    void ReadState(ReadOnlySpan<double> source);
}
