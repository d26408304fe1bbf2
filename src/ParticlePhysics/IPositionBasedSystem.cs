using System;
using ParticlePhysics.Parallel;

namespace ParticlePhysics;

/// <summary>
/// What a position-based integrator (xpbd) needs of a mechanical system, so that it never sees forces: the
/// accelerations of the forces that are not projected, one projection pass of every constraint, and the velocity pass.
/// <see cref="ParticleWorld"/> implements it over its force generators and constraint sets.
/// </summary>
/// <remarks>
/// One substep of h is then: a = <see cref="ComputeUnprojectedAccelerations"/> at its start (x0, v0); v = v0 + h a,
/// x = x0 + h v; <see cref="ProjectConstraints"/>; v = (x - x0) / h; <see cref="SolveConstraintVelocities"/>.
/// </remarks>
public interface IPositionBasedSystem : ISecondOrderSystem
{
    /// <summary>The inverse masses, one per particle: 0 for a pinned particle, which moves only at its own velocity.</summary>
    ReadOnlySpan<double> InverseMasses { get; }

    /// <summary>
    /// The runner the integrator may split its passes over the particles on (<see cref="ParticleWorld.Runner"/>), or
    /// null for the calling thread only; the result must not depend on it.
    /// </summary>
    IParallelRunner? Runner { get; }

    /// <summary>
    /// Writes the accelerations F / m of the forces that no constraint set projects (<see cref="IForceProjection"/>),
    /// without the constraint forces (<see cref="IConstraintForces"/>): the projections enforce those instead.
    /// </summary>
    /// <param name="time">The time t.</param>
    /// <param name="positions">x, 3 values per particle.</param>
    /// <param name="velocities">v, 3 values per particle.</param>
    /// <param name="accelerations">Receives the accelerations, 3 values per particle (0 for pinned particles).</param>
    void ComputeUnprojectedAccelerations(
        double time, ReadOnlySpan<double> positions, ReadOnlySpan<double> velocities, Span<double> accelerations);

    /// <summary>
    /// Projects the predicted positions once onto every constraint (<see cref="IConstraintSet.Project"/> of each set,
    /// in order), for the substep from (<paramref name="startPositions"/>, <paramref name="startVelocities"/>) at
    /// <paramref name="time"/> of length <paramref name="dt"/>.
    /// </summary>
    /// <param name="time">The time at the start of the substep.</param>
    /// <param name="dt">The substep h.</param>
    /// <param name="startPositions">The positions at the start of the substep.</param>
    /// <param name="startVelocities">The velocities at the start of the substep.</param>
    /// <param name="positions">The predicted positions, projected in place.</param>
    /// <param name="velocities">The predicted velocities (the sets may read them).</param>
    void ProjectConstraints(
        double time,
        double dt,
        ReadOnlySpan<double> startPositions,
        ReadOnlySpan<double> startVelocities,
        Span<double> positions,
        Span<double> velocities);

    /// <summary>
    /// Lets every constraint set correct the velocities once (<see cref="IConstraintSet.SolveVelocities"/>: restitution,
    /// friction), after the integrator has set them from the change of positions.
    /// </summary>
    /// <param name="time">The time at the start of the substep.</param>
    /// <param name="dt">The substep h.</param>
    /// <param name="startPositions">The positions at the start of the substep.</param>
    /// <param name="startVelocities">The velocities at the start of the substep (before the solve, for restitution).</param>
    /// <param name="positions">The projected positions.</param>
    /// <param name="velocities">The velocities (x - x0) / h, corrected in place.</param>
    void SolveConstraintVelocities(
        double time,
        double dt,
        ReadOnlySpan<double> startPositions,
        ReadOnlySpan<double> startVelocities,
        Span<double> positions,
        Span<double> velocities);
}
