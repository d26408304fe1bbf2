using System;

namespace ParticlePhysics;

/// <summary>
/// The largest state, in doubles, that a stateful integrator of this library keeps for a system of a given size
/// (<see cref="IStatefulIntegrator.StateLength"/>): what a snapshot admits, and what
/// <see cref="Driver.FixedTimestepDriver"/> reserves so that no frame allocates.
/// </summary>
/// <remarks>
/// 1024 values plus 24 per particle: implicit Euler's warm start is at most eight vectors over the particles, the
/// last four steps' velocity changes and their products (<see cref="Integrators.ImplicitEuler"/>); the adaptive
/// integrator keeps one value. (It was 12 per particle while the warm start remembered two steps, and 6 before it kept
/// their products.)
/// </remarks>
public static class IntegratorStateLimit
{
    /// <summary>The values admitted whatever the system's size.</summary>
    public const int Fixed = 1024;

    /// <summary>The values admitted per particle.</summary>
    public const int PerParticle = 24;

    /// <summary>The largest state for <paramref name="particleCount"/> particles (at most <see cref="int.MaxValue"/>).</summary>
    public static int MaxLength(int particleCount) =>
        (int)Math.Min(int.MaxValue, Fixed + ((long)PerParticle * Math.Max(0, particleCount)));
}
