using System;

namespace ParticlePhysics;

/// <summary>
/// A force acting on some or all particles of a <see cref="ParticleWorld"/>. The system calls each generator
/// once per evaluation (never once per particle), and the generator adds its forces into the accumulator.
/// Generators can be added to and removed from a system at any time without touching the particles.
/// </summary>
/// <example>
/// A uniform wind that pushes every particle with a force proportional to its relative velocity:
/// <code>
/// sealed class Wind : IForceGenerator
/// {
///     public Vector3d AirVelocity { get; set; }
///     public double Coefficient { get; set; } = 0.02;
///     public void AddForces(in ParticleState state, Span&lt;double&gt; forces)
///     {
///         for (int i = 0; i &lt; state.Count; i++)
///         {
///             var f = Coefficient * (AirVelocity - state.Velocity(i));
///             forces[3 * i] += f.X; forces[3 * i + 1] += f.Y; forces[3 * i + 2] += f.Z;
///         }
///     }
/// }
/// </code>
/// </example>
public interface IForceGenerator
{
    /// <summary>
    /// Adds this generator's forces, in newtons, into <paramref name="forces"/> (3 values per particle, already
    /// holding the forces of the generators before it). Must only add, must not allocate, and must depend only on
    /// <paramref name="state"/> and the generator's own parameters, so that repeated evaluations agree.
    /// </summary>
    /// <param name="state">The time, positions, velocities and masses to evaluate at.</param>
    /// <param name="forces">The force accumulator, 3 values per particle.</param>
    void AddForces(in ParticleState state, Span<double> forces);
}
