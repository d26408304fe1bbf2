using System;
using ParticlePhysics.Parallel;

namespace ParticlePhysics;

/// <summary>
/// What the world hands a constraint set (<see cref="IConstraintSet"/>): an interval of time, the state at its start,
/// the state at its end to correct in place, and the particles' masses, as flat buffers of 3 values per particle
/// (one per particle for the masses).
/// </summary>
/// <remarks>
/// After a force-based integrator's step the interval is the whole step; inside the position-based integrator it is
/// one substep. The end state is the world's scratch buffer: it is committed only if every stage succeeds, so a set
/// that throws leaves the world as it was.
/// </remarks>
public readonly ref struct ConstraintContext
{
    /// <summary>Creates a context; the world does this, user code only in tests of its own constraint sets.</summary>
    /// <param name="time">The time at the start of the interval, in seconds.</param>
    /// <param name="dt">The length of the interval, in seconds.</param>
    /// <param name="startPositions">The positions at the start, 3 values per particle.</param>
    /// <param name="startVelocities">The velocities at the start, 3 values per particle.</param>
    /// <param name="positions">The positions at the end, 3 values per particle, to correct in place.</param>
    /// <param name="velocities">The velocities at the end, 3 values per particle, to correct in place.</param>
    /// <param name="masses">The masses, one per particle.</param>
    /// <param name="inverseMasses">The inverse masses, one per particle: 0 for a pinned particle.</param>
    public ConstraintContext(
        double time,
        double dt,
        ReadOnlySpan<double> startPositions,
        ReadOnlySpan<double> startVelocities,
        Span<double> positions,
        Span<double> velocities,
        ReadOnlySpan<double> masses,
        ReadOnlySpan<double> inverseMasses)
        : this(time, dt, startPositions, startVelocities, positions, velocities, masses, inverseMasses, ReadOnlySpan<double>.Empty)
    {
    }

    /// <summary>Creates a context with the particles' radii (what contacts need); the world does this.</summary>
    /// <param name="time">The time at the start of the interval, in seconds.</param>
    /// <param name="dt">The length of the interval, in seconds.</param>
    /// <param name="startPositions">The positions at the start, 3 values per particle.</param>
    /// <param name="startVelocities">The velocities at the start, 3 values per particle.</param>
    /// <param name="positions">The positions at the end, 3 values per particle, to correct in place.</param>
    /// <param name="velocities">The velocities at the end, 3 values per particle, to correct in place.</param>
    /// <param name="masses">The masses, one per particle.</param>
    /// <param name="inverseMasses">The inverse masses, one per particle: 0 for a pinned particle.</param>
    /// <param name="radii">The radii, one per particle, or empty (all points).</param>
    /// <param name="runner">
    /// The runner a set with much work may split it over (<see cref="ParticleWorld.Runner"/>), or null to run on the
    /// calling thread; the result must be bit-identical either way.
    /// </param>
    public ConstraintContext(
        double time,
        double dt,
        ReadOnlySpan<double> startPositions,
        ReadOnlySpan<double> startVelocities,
        Span<double> positions,
        Span<double> velocities,
        ReadOnlySpan<double> masses,
        ReadOnlySpan<double> inverseMasses,
        ReadOnlySpan<double> radii,
        IParallelRunner? runner = null)
        : this(time, dt, startPositions, startVelocities, positions, velocities, masses, inverseMasses, radii, runner, kickDrift: false)
    {
    }

    /// <summary>Creates a context that says how the end state was reached; the world does this.</summary>
    /// <param name="time">The time at the start of the interval, in seconds.</param>
    /// <param name="dt">The length of the interval, in seconds.</param>
    /// <param name="startPositions">The positions at the start, 3 values per particle.</param>
    /// <param name="startVelocities">The velocities at the start, 3 values per particle.</param>
    /// <param name="positions">The positions at the end, 3 values per particle, to correct in place.</param>
    /// <param name="velocities">The velocities at the end, 3 values per particle, to correct in place.</param>
    /// <param name="masses">The masses, one per particle.</param>
    /// <param name="inverseMasses">The inverse masses, one per particle: 0 for a pinned particle.</param>
    /// <param name="radii">The radii, one per particle, or empty (all points).</param>
    /// <param name="runner">The runner a set may split its work over, or null.</param>
    /// <param name="kickDrift">
    /// Whether the end state came from one kick and one drift over the interval (<see cref="IKickDriftIntegrator"/>):
    /// see <see cref="KickDrift"/>.
    /// </param>
    public ConstraintContext(
        double time,
        double dt,
        ReadOnlySpan<double> startPositions,
        ReadOnlySpan<double> startVelocities,
        Span<double> positions,
        Span<double> velocities,
        ReadOnlySpan<double> masses,
        ReadOnlySpan<double> inverseMasses,
        ReadOnlySpan<double> radii,
        IParallelRunner? runner,
        bool kickDrift)
        : this(time, dt, startPositions, startVelocities, positions, velocities, masses, inverseMasses, radii, runner, kickDrift, sleeping: null)
    {
    }

    /// <summary>
    /// A context with the world's sleeping (<see cref="ISleepingParticles"/>): its sleeping particles have inverse mass 0
    /// in <paramref name="inverseMasses"/>, and a set may wake them through <paramref name="sleeping"/>.
    /// </summary>
    public ConstraintContext(
        double time,
        double dt,
        ReadOnlySpan<double> startPositions,
        ReadOnlySpan<double> startVelocities,
        Span<double> positions,
        Span<double> velocities,
        ReadOnlySpan<double> masses,
        ReadOnlySpan<double> inverseMasses,
        ReadOnlySpan<double> radii,
        IParallelRunner? runner,
        bool kickDrift,
        ISleepingParticles? sleeping)
    {
        var n = 3 * masses.Length;
        if (startPositions.Length != n || startVelocities.Length != n || positions.Length != n || velocities.Length != n
            || inverseMasses.Length != masses.Length || (radii.Length != 0 && radii.Length != masses.Length))
        {
            throw new ArgumentException(
                "positions and velocities need 3 values per particle, masses and inverse masses one each, and radii one each or none.");
        }

        Time = time;
        Dt = dt;
        Runner = runner;
        KickDrift = kickDrift;
        StartPositions = startPositions;
        StartVelocities = startVelocities;
        Positions = positions;
        Velocities = velocities;
        Masses = masses;
        InverseMasses = inverseMasses;
        Radii = radii;
        Sleeping = sleeping;
    }

    /// <summary>The world's sleeping, or null when no particle can sleep (then no inverse mass is 0 for sleep).</summary>
    public ISleepingParticles? Sleeping { get; }

    /// <summary>The time at the start of the interval, in seconds.</summary>
    public double Time { get; }

    /// <summary>The length of the interval, in seconds.</summary>
    public double Dt { get; }

    /// <summary>
    /// The runner a set with much work may split it over (the world's <see cref="ParticleWorld.Runner"/>), or null.
    /// Chunks of one call must touch disjoint data, so that the result does not depend on the runner.
    /// </summary>
    public IParallelRunner? Runner { get; }

    /// <summary>
    /// True when the end state came from one kick and one drift over the whole interval, v1 = v0 + dt a(x0, v0) and
    /// x1 = x0 + dt v1 (the world's step with an <see cref="IKickDriftIntegrator"/>: semi-implicit Euler). A set that
    /// moves an end position by dx may then change that particle's end velocity by dx / dt, which keeps the end state a
    /// kick and a drift: the correction becomes part of the kick's impulse. False after any other integrator and in
    /// xpbd's substeps.
    /// </summary>
    public bool KickDrift { get; }

    /// <summary>The number of particles.</summary>
    public int Count => Masses.Length;

    /// <summary>The positions at the start of the interval, 3 values per particle.</summary>
    public ReadOnlySpan<double> StartPositions { get; }

    /// <summary>The velocities at the start of the interval, 3 values per particle.</summary>
    public ReadOnlySpan<double> StartVelocities { get; }

    /// <summary>The positions at the end of the interval, 3 values per particle: correct them in place.</summary>
    public Span<double> Positions { get; }

    /// <summary>The velocities at the end of the interval, 3 values per particle: correct them in place.</summary>
    public Span<double> Velocities { get; }

    /// <summary>The masses, one per particle, in kilograms.</summary>
    public ReadOnlySpan<double> Masses { get; }

    /// <summary>The inverse masses, one per particle: 1 / m, or 0 for a pinned particle (which no constraint moves).</summary>
    public ReadOnlySpan<double> InverseMasses { get; }

    /// <summary>
    /// The radii, one per particle, in metres (<see cref="ParticleWorld.Radii"/>), or empty when the context was made
    /// without them: every particle is then a point (radius 0). The world always passes them.
    /// </summary>
    public ReadOnlySpan<double> Radii { get; }
}
