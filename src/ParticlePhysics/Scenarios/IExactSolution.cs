using System;

namespace ParticlePhysics.Scenarios;

/// <summary>A scenario whose exact (analytic) solution is known, in the layout of its system's state vector.</summary>
public interface IExactSolution
{
    /// <summary>Writes the exact state vector at <paramref name="time"/> into <paramref name="state"/>.</summary>
    /// <param name="time">The time, in seconds from the start.</param>
    /// <param name="state">Receives the state, laid out as the scenario's system lays out its own.</param>
    void ExactState(double time, Span<double> state);
}
