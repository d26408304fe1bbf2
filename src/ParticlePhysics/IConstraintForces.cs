using System;

namespace ParticlePhysics;

/// <summary>
/// Constraints that act through forces under the force-based integrators: at every evaluation, after the force
/// generators, the world hands them the state and the applied forces Q, and they add the constraint forces that keep
/// the constraints' second derivative at zero (Witkin and Baraff, "Constrained Dynamics"). A constraint set that
/// implements it (rods, taut cables) then holds its constraints exactly along the integrator's own stages, so every
/// integrator keeps its order; its <see cref="IConstraintSet.Resolve"/> only removes the drift that remains.
/// </summary>
/// <remarks>
/// The world calls it from <see cref="ParticleWorld.AccumulateForces"/> (and so from every evaluation and
/// acceleration), in the order the sets were added, but never from the position-based integrator's predictions,
/// which leave such constraints to <see cref="IConstraintSet.Project"/>. It must not allocate and must be
/// deterministic. A set that also implements <see cref="IForceJacobian"/> enters the implicit step's linearisation
/// (<see cref="ILinearizableSystem"/>) after the generators: the world calls its <see cref="IForceJacobian.Linearize"/>
/// right after its <see cref="AddConstraintForces"/> at the same state, so it may linearise the multipliers it has just
/// solved for (the rods give the geometric stiffness of their tensions).
/// </remarks>
public interface IConstraintForces
{
    /// <summary>
    /// Adds the constraint forces J^T lambda into <paramref name="forces"/>, which holds on entry the applied forces Q
    /// of every generator (3 values per particle), for the state <paramref name="state"/>.
    /// </summary>
    /// <param name="state">The time, positions, velocities, masses and inverse masses of the evaluation.</param>
    /// <param name="forces">The force accumulator: the applied forces on entry, the applied plus constraint forces on return.</param>
    void AddConstraintForces(in ParticleState state, Span<double> forces);
}
