using System;
using ParticlePhysics.Numerics;
using ParticlePhysics.Parallel;

namespace ParticlePhysics;

/// <summary>
/// What a force generator sees during one evaluation: the time and a read-only view of positions,
/// velocities and masses, as flat buffers of 3 doubles per particle (x0, y0, z0, x1, ...).
/// The positions and velocities are those of the integrator's current stage, not necessarily
/// the particle system's committed state.
/// </summary>
public readonly ref struct ParticleState
{
    /// <summary>Creates a view; the engine does this, user code only in tests of its own forces.</summary>
    /// <param name="time">The time of the evaluation.</param>
    /// <param name="positions">3 values per particle.</param>
    /// <param name="velocities">3 values per particle.</param>
    /// <param name="masses">One value per particle.</param>
    /// <param name="inverseMasses">One value per particle: 1 / m, or 0 for a pinned particle.</param>
    /// <param name="runner">The runner a generator may split its work over, or null to run on the calling thread.</param>
    public ParticleState(
        double time,
        ReadOnlySpan<double> positions,
        ReadOnlySpan<double> velocities,
        ReadOnlySpan<double> masses,
        ReadOnlySpan<double> inverseMasses,
        IParallelRunner? runner = null)
    {
        if (positions.Length != 3 * masses.Length || velocities.Length != positions.Length
            || inverseMasses.Length != masses.Length)
        {
            throw new ArgumentException(
                "positions and velocities need 3 values per particle, and masses and inverse masses one each.");
        }

        Time = time;
        Positions = positions;
        Velocities = velocities;
        Masses = masses;
        InverseMasses = inverseMasses;
        Runner = runner;
    }

    /// <summary>The time of the evaluation, in seconds.</summary>
    public double Time { get; }

    /// <summary>The number of particles.</summary>
    public int Count => Masses.Length;

    /// <summary>Positions, 3 values per particle, in metres.</summary>
    public ReadOnlySpan<double> Positions { get; }

    /// <summary>Velocities, 3 values per particle, in metres per second.</summary>
    public ReadOnlySpan<double> Velocities { get; }

    /// <summary>Masses, one per particle, in kilograms (a pinned particle keeps the mass it was given).</summary>
    public ReadOnlySpan<double> Masses { get; }

    /// <summary>Inverse masses, one per particle: 1 / m for a free particle, 0 for a pinned one.</summary>
    public ReadOnlySpan<double> InverseMasses { get; }

    /// <summary>
    /// The runner that a generator with much work may split it over (<see cref="ParticleWorld.Runner"/>), or null.
    /// A generator that uses it must produce bit-identical forces with and without it.
    /// </summary>
    public IParallelRunner? Runner { get; }

    /// <summary>The position of particle <paramref name="index"/>.</summary>
    public Vector3d Position(int index)
    {
        var x = Positions.ForReading();
        return new(x[3 * index], x[(3 * index) + 1], x[(3 * index) + 2]);
    }

    /// <summary>The velocity of particle <paramref name="index"/>.</summary>
    public Vector3d Velocity(int index)
    {
        var v = Velocities.ForReading();
        return new(v[3 * index], v[(3 * index) + 1], v[(3 * index) + 2]);
    }
}
