using System;
using System.Numerics;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Driver;

/// <summary>
/// Runs a <see cref="ParticleWorld"/> at a fixed time step from a game loop whose frames take any time, after
/// Glenn Fiedler's "Fix Your Timestep": each frame's elapsed time is added to an accumulator, whole fixed steps are
/// taken out of it, and the remainder is carried to the next frame. Rendering blends the last two states with
/// <see cref="InterpolationFactor"/>.
/// </summary>
/// <remarks>
/// accumulator += frameTime; while accumulator &gt;= dt: previous = x; step(dt); accumulator -= dt;
/// alpha = accumulator / dt; rendered = (1 - alpha) previous + alpha x.
/// The physics only ever sees steps of exactly dt (or dt / <see cref="SubSteps"/>), so the state after k fixed steps is
/// bit-identical whatever frame times produced them. A frame that would need more than
/// <see cref="MaxStepsPerFrame"/> steps (after a pause or a hitch) runs that many and drops the rest of the whole
/// steps (<see cref="LastDroppedTime"/>): the simulation falls behind the wall clock instead of freezing the game in a
/// spiral of ever longer frames. Nothing here allocates once constructed.
/// All or nothing: a frame whose steps do not all succeed (a step diverges, a force throws, a solver gives up) leaves
/// the world (state and time), the integrator's state, the accumulator, the interpolation and the counters exactly as
/// they were before the call, and rethrows. For that, a frame of two or more integrator steps first copies the state
/// (and the integrator's state) aside, one copy of 6 doubles per particle: a frame of one step needs no copy, since
/// <see cref="ParticleWorld.Step"/> is all or nothing itself.
/// </remarks>
public sealed class FixedTimestepDriver
{
    /// <summary>The default <see cref="MaxStepsPerFrame"/>: 8, a quarter second of steps at 30 Hz, 0.13 s at 60 Hz.</summary>
    public const int DefaultMaxStepsPerFrame = 8;

    private readonly double _subStep;
    private double[] _previous;
    private double[] _pendingPrevious;
    private double _accumulator;

    // The frame's starting point, restored if any of its steps fails.
    private readonly double[] _frameState;
    private double[] _frameIntegratorState = Array.Empty<double>();

    /// <summary>Creates a driver.</summary>
    /// <param name="system">The system to advance; its particle count must not change while this driver runs it.</param>
    /// <param name="integrator">The integrator of every step (it keeps its own scratch buffers: one per system).</param>
    /// <param name="fixedTimeStep">dt, the simulated time of one fixed step, in seconds; 1/60 or 1/50 is usual.</param>
    /// <param name="subSteps">
    /// How many integrator steps of dt / <paramref name="subSteps"/> make one fixed step (default 1); more sub-steps
    /// keep a stiff cloth stable with an explicit integrator while rendering still sees one state per dt.
    /// </param>
    /// <param name="maxStepsPerFrame">The most fixed steps one call to <see cref="Advance"/> runs (default 8).</param>
    public FixedTimestepDriver(
        ParticleWorld system,
        IIntegrator integrator,
        double fixedTimeStep,
        int subSteps = 1,
        int maxStepsPerFrame = DefaultMaxStepsPerFrame)
    {
        Guard.NotNull(system, nameof(system));
        Guard.NotNull(integrator, nameof(integrator));
        Guard.PositiveFinite(fixedTimeStep, nameof(fixedTimeStep));
        if (subSteps < 1)
        {
            throw new ArgumentOutOfRangeException(
                nameof(subSteps), subSteps, $"subSteps must be at least 1; got {subSteps}.");
        }

        if (maxStepsPerFrame < 1)
        {
            throw new ArgumentOutOfRangeException(
                nameof(maxStepsPerFrame), maxStepsPerFrame, $"maxStepsPerFrame must be at least 1; got {maxStepsPerFrame}.");
        }

        System = system;
        Integrator = integrator;
        FixedTimeStep = fixedTimeStep;
        SubSteps = subSteps;
        MaxStepsPerFrame = maxStepsPerFrame;
        _subStep = fixedTimeStep / subSteps;
        _previous = new double[system.CoordinateCount];
        _pendingPrevious = new double[system.CoordinateCount];
        _frameState = new double[system.Dimension];

        // Room for the integrator's state up front, so that no frame allocates: implicit Euler's grows to 1 + 24 values
        // per particle over its first steps; IntegratorStateLimit is what a snapshot admits of any integrator.
        _frameIntegratorState = integrator is IStatefulIntegrator stateful
            ? new double[Math.Max(stateful.StateLength, IntegratorStateLimit.MaxLength(system.Count))]
            : Array.Empty<double>();
        system.Positions.CopyTo(_previous);
    }

    /// <summary>The system this driver advances.</summary>
    public ParticleWorld System { get; }

    /// <summary>The integrator of every step.</summary>
    public IIntegrator Integrator { get; }

    /// <summary>dt, the simulated time of one fixed step, in seconds.</summary>
    public double FixedTimeStep { get; }

    /// <summary>The number of integrator steps of dt / <see cref="SubSteps"/> in one fixed step.</summary>
    public int SubSteps { get; }

    /// <summary>The most fixed steps one call to <see cref="Advance"/> runs.</summary>
    public int MaxStepsPerFrame { get; }

    /// <summary>The frame time not yet simulated, in seconds: at least 0 and less than <see cref="FixedTimeStep"/> between frames.</summary>
    public double Accumulator => _accumulator;

    /// <summary>
    /// alpha = <see cref="Accumulator"/> / dt, in [0, 1): how far the render time lies between the state before the
    /// last fixed step (alpha = 0) and the current state (alpha = 1).
    /// </summary>
    public double InterpolationFactor => _accumulator / FixedTimeStep;

    /// <summary>Fixed steps run since the driver was created.</summary>
    public long StepCount { get; private set; }

    /// <summary>The time the last call to <see cref="Advance"/> dropped because of <see cref="MaxStepsPerFrame"/>, in seconds.</summary>
    public double LastDroppedTime { get; private set; }

    /// <summary>All the time dropped because of <see cref="MaxStepsPerFrame"/> since the driver was created, in seconds.</summary>
    public double TotalDroppedTime { get; private set; }

    /// <summary>
    /// Adds a frame's elapsed time and runs the whole fixed steps it completes, at most <see cref="MaxStepsPerFrame"/>.
    /// </summary>
    /// <param name="frameTime">The frame's elapsed time in seconds (Unity's Time.deltaTime): finite and &gt;= 0.</param>
    /// <returns>The number of fixed steps run.</returns>
    /// <exception cref="ArgumentOutOfRangeException"><paramref name="frameTime"/> is negative, NaN or infinite.</exception>
    /// <exception cref="InvalidOperationException">Called from inside the world's own step (a force that advances the driver).</exception>
    /// <exception cref="SimulationDivergedException">
    /// A step diverged. Nothing of the frame is kept: the world, the integrator, the accumulator and the interpolation
    /// are as they were before the call, and the exception's <see cref="SimulationDivergedException.LastFiniteTime"/>
    /// is the time the frame started from. Retry with more sub-steps or another integrator (a new driver).
    /// </exception>
    /// <remarks>Any other exception from a step (a force that throws, a solver that gives up) leaves everything as it was too.</remarks>
    public int Advance(double frameTime)
    {
        // From inside the world's own step (a force that advances its driver) the frame could neither run nor rewind:
        // refused before the frame's bracket opens.
        System.ThrowIfStepping();
        Guard.NonNegativeFinite(frameTime, nameof(frameTime));
        if (System.CoordinateCount != _previous.Length)
        {
            throw new InvalidOperationException(
                $"The system has {System.Count} particles, but this driver was created for {_previous.Length / 3}: "
                + "create a new driver after adding particles.");
        }

        // The frame's arithmetic on a copy of the accumulator: nothing is kept unless every step succeeds.
        var accumulator = _accumulator + frameTime;
        var dt = FixedTimeStep;
        var steps = 0;
        while (accumulator >= dt && steps < MaxStepsPerFrame)
        {
            accumulator -= dt;
            steps++;
        }

        if (steps > 0)
        {
            RunSteps(steps);
        }

        var dropped = 0.0;
        if (accumulator >= dt)
        {
            // Drop the whole steps and keep the fraction of a step, so that the interpolation stays smooth.
            // % on doubles is fmod: exact, and in [0, dt) for a positive accumulator.
            var remainder = accumulator % dt;
            dropped = accumulator - remainder;
            accumulator = remainder;
        }

        _accumulator = accumulator;
        StepCount += steps;
        LastDroppedTime = dropped;
        TotalDroppedTime += dropped;
        return steps;
    }

    /// <summary>Runs <paramref name="steps"/> fixed steps, all of them or, if one fails, none.</summary>
    private void RunSteps(int steps)
    {
        var stateful = Integrator as IStatefulIntegrator;
        var checkpoint = (steps * (long)SubSteps) > 1;
        var startTime = System.Time;
        var integratorStateLength = 0;
        if (checkpoint)
        {
            // One step of the world is all or nothing by itself; more need the frame's start kept aside.
            System.State.CopyTo(_frameState);
            if (stateful is not null)
            {
                integratorStateLength = stateful.StateLength;
                if (_frameIntegratorState.Length < integratorStateLength)
                {
                    _frameIntegratorState = new double[integratorStateLength];
                }

                stateful.WriteState(_frameIntegratorState.AsSpan(0, integratorStateLength));
            }
        }

        // The constraint sets' logs (impacts, tensions) follow the frame as one bracket: restored with the state.
        if (checkpoint)
        {
            System.BeginFrame();
        }

        try
        {
            for (var step = 0; step < steps; step++)
            {
                System.Positions.CopyTo(_pendingPrevious);
                for (var s = 0; s < SubSteps; s++)
                {
                    System.Step(Integrator, _subStep);
                }
            }
        }
        catch (SimulationDivergedException diverged) when (checkpoint)
        {
            Rewind(stateful, startTime, integratorStateLength);
            System.EndFrame(committed: false);
            throw diverged.RewoundTo(startTime);
        }
        catch when (checkpoint)
        {
            Rewind(stateful, startTime, integratorStateLength);
            System.EndFrame(committed: false);
            throw;
        }

        if (checkpoint)
        {
            System.EndFrame(committed: true);
        }

        // The positions before the frame's last fixed step are the interpolation's start.
        (_previous, _pendingPrevious) = (_pendingPrevious, _previous);
    }

    private void Rewind(IStatefulIntegrator? stateful, double startTime, int integratorStateLength)
    {
        System.SetState(_frameState);
        System.Time = startTime;
        stateful?.ReadState(_frameIntegratorState.AsSpan(0, integratorStateLength));
    }

    /// <summary>
    /// Forgets the state before the last step, so that rendering shows the current state whatever the interpolation
    /// factor: call it after moving particles by hand (a teleport) or restoring a snapshot.
    /// </summary>
    public void ResetInterpolation()
    {
        System.ThrowIfStepping(); // inside a frame: a failed frame must leave the interpolation as it was
        if (System.CoordinateCount != _previous.Length)
        {
            throw new InvalidOperationException(
                $"The system has {System.Count} particles, but this driver was created for {_previous.Length / 3}.");
        }

        System.Positions.CopyTo(_previous);
    }

    /// <summary>
    /// Clears the accumulator (and the interpolation), for instance after restoring a snapshot taken between frames.
    /// </summary>
    public void Reset()
    {
        System.ThrowIfStepping(); // inside a frame: a failed frame must leave the accumulator as it was
        _accumulator = 0.0;
        LastDroppedTime = 0.0;
        ResetInterpolation();
    }

    /// <summary>
    /// Writes the positions at render time, (1 - alpha) previous + alpha current with alpha =
    /// <see cref="InterpolationFactor"/>, rounded to single precision, one vector per particle, for every particle of
    /// the system. Allocates nothing.
    /// </summary>
    /// <param name="destination">At least <see cref="ParticleWorld.Count"/> vectors (Unity's Mesh.SetVertices layout).</param>
    public void InterpolatePositions(Span<Vector3> destination) => InterpolatePositions(0, System.Count, destination);

    /// <summary>
    /// Writes the interpolated positions of particles <paramref name="firstParticle"/> to
    /// <paramref name="firstParticle"/> + <paramref name="count"/> - 1 into <paramref name="destination"/>[0..count):
    /// one cloth's vertices in a system that holds several bodies.
    /// </summary>
    /// <param name="firstParticle">The first particle to write.</param>
    /// <param name="count">How many particles to write.</param>
    /// <param name="destination">At least <paramref name="count"/> vectors.</param>
    public void InterpolatePositions(int firstParticle, int count, Span<Vector3> destination)
    {
        if (firstParticle < 0 || count < 0 || firstParticle > System.Count - count)
        {
            throw new ArgumentOutOfRangeException(
                nameof(count),
                count,
                $"particles {firstParticle} to {firstParticle + count - 1} must exist; the system has {System.Count}.");
        }

        if (destination.Length < count)
        {
            throw new ArgumentException(
                $"destination must hold at least {count} vectors; it holds {destination.Length}.", nameof(destination));
        }

        if (System.CoordinateCount != _previous.Length)
        {
            throw new InvalidOperationException(
                $"The system has {System.Count} particles, but this driver was created for {_previous.Length / 3}.");
        }

        var alpha = InterpolationFactor;
        var beta = 1.0 - alpha;
        var current = System.Positions.ForReading();
        var previous = _previous;
        for (var i = 0; i < count; i++)
        {
            var o = 3 * (firstParticle + i);
            destination[i] = new Vector3(
                (float)((beta * previous[o]) + (alpha * current[o])),
                (float)((beta * previous[o + 1]) + (alpha * current[o + 1])),
                (float)((beta * previous[o + 2]) + (alpha * current[o + 2])));
        }
    }
}
