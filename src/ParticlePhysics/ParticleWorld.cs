using System;
using System.Collections.Generic;
using System.Globalization;
using System.Numerics;
using ParticlePhysics.Numerics;
using ParticlePhysics.Parallel;

namespace ParticlePhysics;

/// <summary>
/// The course's state vector of N point masses: positions and velocities in one flat buffer of 6 N doubles,
/// laid out [x0 y0 z0 x1 ... | vx0 vy0 vz0 vx1 ...], a mass per particle, a force accumulator, pinned particles,
/// and a list of force generators that can change at any time. It is an <see cref="IOdeSystem"/>
/// (dy/dt = [v | F / m]), an <see cref="ISecondOrderSystem"/>, an <see cref="ILinearizableSystem"/> (its forces'
/// Jacobians, for implicit steps) and an <see cref="IPositionBasedSystem"/> (accelerations and projections for xpbd),
/// so every integrator can advance it.
/// </summary>
/// <remarks>
/// Positions first, then velocities (rather than interleaved per particle) so that integrators that treat the two
/// differently work on two contiguous halves. While particles are being added, the buffer keeps spare capacity in
/// each half; it is compacted to exactly 6 N values at the first step, so building a large cloth stays linear.
/// A pinned particle has infinite mass (inverse mass 0): no force changes its velocity, so every integrator moves it
/// at exactly the velocity it has, zero (the default: it stays where it is) or the velocity the host gives it to
/// drive it along a path (a kinematic particle, see <see cref="MoveKinematic"/>). Stepping allocates nothing once
/// the system and its integrator have been used once.
/// </remarks>
public sealed class ParticleWorld : ILinearizableSystem, IPositionBasedSystem, ICouplingRevision, IJacobianProductTail
{
    private readonly List<IForceGenerator> _forceGenerators = new();
    private readonly List<IConstraintSet> _constraintSets = new();

    // The sets that add constraint forces at every evaluation (rods under the force-based integrators), and the
    // generators that no set projects (what xpbd's predictions see), rebuilt when generators or sets change.
    private readonly List<IConstraintForces> _constraintForces = new();
    private readonly List<IForceGenerator> _unprojected = new();
    private bool _unprojectedStale = true;

    // The implicit stepper's linearisation (ILinearizableSystem): the generators linearised at the last Linearize,
    // and the finite-difference wrappers of those that supply no Jacobian of their own, kept while they are added.
    private readonly List<IForceJacobian> _linearized = new();
    private readonly List<int> _linearizedSource = new(); // the index of each entry's generator, increasing
    private readonly Dictionary<IForceGenerator, FiniteDifferenceJacobian> _finiteDifference = new();
    private double[] _state = Array.Empty<double>();
    private double[] _masses = Array.Empty<double>();
    private double[] _inverseMasses = Array.Empty<double>();
    private bool[] _pinned = Array.Empty<bool>();
    private double[] _radii = Array.Empty<double>();
    private double[] _forces = Array.Empty<double>();
    private double[] _next = Array.Empty<double>();
    private int _capacity;
    private int _count;

    // Bumped whenever particles or generators are added or removed: products and blocks need a Linearize of the
    // world as it is (its buffers' sizes and its generators' linearisations follow the particles and the generators).
    private int _structureVersion;
    private int _linearizedVersion = -1;

    // This world's number among the worlds of the process (ICouplingRevision: a revision no other world gives).
    private static long _worldsCreated;
    private readonly long _worldNumber = System.Threading.Interlocked.Increment(ref _worldsCreated);
    private bool _stepping;
    private int _frameDepth; // open FixedTimestepDriver frames: their steps leave the constraint sets' bracket to them
    private double _time;
    private double _divergenceLimit = DefaultDivergenceLimit;
    private IParallelRunner? _runner;

    /// <summary>Creates an empty particle system.</summary>
    /// <param name="capacity">How many particles to make room for up front (optional).</param>
    public ParticleWorld(int capacity = 0)
    {
        if (capacity < 0 || capacity > MaxParticles)
        {
            throw new ArgumentOutOfRangeException(
                nameof(capacity), capacity, $"capacity must be 0 to {MaxParticles}; got {capacity}.");
        }

        Reallocate(capacity);
    }

    /// <summary>
    /// The most particles a world may hold: 2048 x 2048 = 4,194,304 (a state of 200 MB). Far beyond what a game
    /// steps per frame, and small enough that every buffer size, 9 values per particle at most, fits an array.
    /// </summary>
    public const int MaxParticles = 2048 * 2048;

    /// <summary>The default <see cref="DivergenceLimit"/>: 1e12 m/s, some 3,000 times the speed of light.</summary>
    public const double DefaultDivergenceLimit = 1e12;

    /// <summary>The number of particles.</summary>
    public int Count => _count;

    /// <summary>
    /// The runner over which force generators may split large evaluations (a spring network of thousands of
    /// springs), or null (the default) to compute everything on the calling thread. Results are bit-identical either
    /// way. The system does not own the runner: dispose a <see cref="WorkerThreadRunner"/> yourself. Set it between
    /// steps: like every change to the world, setting it from inside the world's own step throws.
    /// </summary>
    public IParallelRunner? Runner
    {
        get => _runner;
        set
        {
            ThrowIfStepping();
            _runner = value;
        }
    }

    /// <summary>
    /// The largest magnitude a velocity component may reach, in m/s: a step that produces a faster particle, or any
    /// position or velocity that is NaN or infinite, throws <see cref="SimulationDivergedException"/> and is not
    /// committed. Positions may take any finite value, so a world of any size runs (a free fall from 1.1e12 m as one
    /// from 300 m). The default, 1e12 m/s (3,000 times the speed of light), is beyond any game world or course
    /// scenario, yet catches a blow-up long before it overflows, so the state left in place is one worth retrying
    /// from: positions grow only through velocities, and an unstable cloth's speeds pass 1e12 m/s within a quarter
    /// second, seconds before anything reaches infinity. The bound is on speeds rather than on coordinates because a
    /// coordinate bound must know the world's size, and one taken from the world itself either follows the blow-up
    /// (from the current state) or depends on history that a snapshot does not hold; a speed bound depends only on the
    /// step's result. Set <see cref="double.MaxValue"/> to stop only at non-finite values.
    /// </summary>
    public double DivergenceLimit
    {
        get => _divergenceLimit;
        set
        {
            ThrowIfStepping();
            Guard.PositiveFinite(value, nameof(DivergenceLimit));
            _divergenceLimit = value;
        }
    }

    /// <summary>The simulated time, in seconds: advanced by each <see cref="Step"/>.</summary>
    public double Time
    {
        get => _time;
        set
        {
            ThrowIfStepping();
            Guard.Finite(value, nameof(Time));
            _time = value;
        }
    }

    /// <summary>The dimension of the state vector: 6 values per particle.</summary>
    public int Dimension => 6 * _count;

    /// <summary>The number of position coordinates: 3 per particle.</summary>
    public int CoordinateCount => 3 * _count;

    /// <summary>The force generators, in the order they are evaluated.</summary>
    public IReadOnlyList<IForceGenerator> Forces => _forceGenerators;

    /// <summary>The constraint sets (rods, cables, contacts, ...), in the order their stage applies them.</summary>
    public IReadOnlyList<IConstraintSet> Constraints => _constraintSets;

    /// <summary>The positions, 3 values per particle (x0, y0, z0, x1, ...). Valid until the system next changes.</summary>
    public ReadOnlySpan<double> Positions => _state.AsSpan(0, 3 * _count);

    /// <summary>The velocities, 3 values per particle. Valid until the system next changes.</summary>
    public ReadOnlySpan<double> Velocities => _state.AsSpan(3 * _capacity, 3 * _count);

    /// <summary>The masses, one per particle (a pinned particle keeps its mass; it is its inverse that is 0).</summary>
    public ReadOnlySpan<double> Masses => _masses.AsSpan(0, _count);

    /// <summary>The inverse masses, one per particle: 1 / m, or 0 for a pinned particle.</summary>
    public ReadOnlySpan<double> InverseMasses => _inverseMasses.AsSpan(0, _count);

    /// <summary>
    /// The radii, one per particle, in metres (0, the default, for a point): what contacts see of a particle's size.
    /// </summary>
    public ReadOnlySpan<double> Radii => _radii.AsSpan(0, _count);

    /// <summary>
    /// The whole state vector [positions | velocities], 6 values per particle: the buffer the integrators advance.
    /// Valid until the system next changes.
    /// </summary>
    public ReadOnlySpan<double> State
    {
        get
        {
            Compact();
            return _state.AsSpan(0, 6 * _count);
        }
    }

    /// <summary>The forces of the last evaluation (3 values per particle), for inspection and debugging.</summary>
    public ReadOnlySpan<double> LastForces => _forces.AsSpan(0, 3 * _count);

    /// <summary>Adds a particle at rest.</summary>
    /// <param name="position">Its position, in metres.</param>
    /// <param name="mass">Its mass, a positive finite number of kilograms.</param>
    /// <returns>The new particle's index (particles are numbered in creation order from 0).</returns>
    public int AddParticle(Vector3d position, double mass) => AddParticle(position, Vector3d.Zero, mass);

    /// <summary>Adds a particle.</summary>
    /// <param name="position">Its position, in metres.</param>
    /// <param name="velocity">Its velocity, in metres per second.</param>
    /// <param name="mass">Its mass, a positive finite number of kilograms (pin it to make it immovable).</param>
    /// <returns>The new particle's index (particles are numbered in creation order from 0).</returns>
    public int AddParticle(Vector3d position, Vector3d velocity, double mass)
    {
        ThrowIfStepping();
        Guard.Finite(position, nameof(position));
        Guard.Finite(velocity, nameof(velocity));
        Guard.Mass(mass, nameof(mass));
        if (_count == MaxParticles)
        {
            throw new InvalidOperationException($"A world holds at most {MaxParticles} particles; this one is full.");
        }

        if (_count == _capacity)
        {
            Reallocate(Math.Min(MaxParticles, Math.Max(4, 2 * _capacity)));
        }

        var index = _count++;
        _structureVersion++;
        WritePosition(index, position);
        WriteVelocity(index, velocity);
        _masses[index] = mass;
        _inverseMasses[index] = 1.0 / mass;
        _pinned[index] = false;
        _radii[index] = 0.0;
        return index;
    }

    /// <summary>The position of a particle, in metres.</summary>
    public Vector3d GetPosition(int index)
    {
        Guard.ParticleIndex(index, _count, nameof(index));
        return new Vector3d(_state[3 * index], _state[(3 * index) + 1], _state[(3 * index) + 2]);
    }

    /// <summary>Moves a particle (pinned particles too: this is how a host drags an attachment point).</summary>
    public void SetPosition(int index, Vector3d position)
    {
        ThrowIfStepping();
        Guard.ParticleIndex(index, _count, nameof(index));
        Guard.Finite(position, nameof(position));
        WritePosition(index, position);
    }

    /// <summary>The velocity of a particle, in metres per second.</summary>
    public Vector3d GetVelocity(int index)
    {
        Guard.ParticleIndex(index, _count, nameof(index));
        var o = (3 * _capacity) + (3 * index);
        return new Vector3d(_state[o], _state[o + 1], _state[o + 2]);
    }

    /// <summary>
    /// Sets the velocity of a particle. A pinned particle then moves at exactly this velocity, whatever acts on it (a
    /// kinematic particle, an anchor the host moves), and springs, dampers and drag see it.
    /// </summary>
    public void SetVelocity(int index, Vector3d velocity)
    {
        ThrowIfStepping();
        Guard.ParticleIndex(index, _count, nameof(index));
        Guard.Finite(velocity, nameof(velocity));
        WriteVelocity(index, velocity);
    }

    /// <summary>
    /// Drives a pinned particle along a path the host knows: gives it the velocity (target - x) / duration, so that it
    /// reaches <paramref name="target"/> after <paramref name="duration"/> seconds of steps, and springs, dampers and
    /// drag see the path's velocity (moving it with <see cref="SetPosition"/> alone would leave it at rest for them).
    /// Call it once per frame with the anchor's next position.
    /// </summary>
    /// <exception cref="InvalidOperationException">The particle is not pinned (forces move a free particle).</exception>
    /// <exception cref="ArgumentOutOfRangeException">
    /// The target is not finite, or so far that target - x overflows; the duration is not positive and finite, or so
    /// short that the velocity overflows. Nothing is changed.
    /// </exception>
    public void MoveKinematic(int index, Vector3d target, double duration)
    {
        ThrowIfStepping();
        Guard.ParticleIndex(index, _count, nameof(index));
        Guard.Finite(target, nameof(target));
        Guard.PositiveFinite(duration, nameof(duration));
        if (!_pinned[index])
        {
            throw new InvalidOperationException(
                $"Particle {index} is not pinned: forces move it. Pin it to drive it along a path.");
        }

        WriteVelocity(index, KinematicVelocity(index, target, duration, nameof(target)));
    }

    /// <summary>
    /// The velocity (target - x) / duration that takes particle <paramref name="index"/> to <paramref name="target"/>
    /// in <paramref name="duration"/> seconds (both finite, the duration positive), or an exception that names what is
    /// out of range. The difference comes first, so a particle already there gets 0 at any duration; it is scaled by
    /// 1 / duration (the bits of every run before), and divided instead where that is not finite: below
    /// 1 / double.MaxValue (about 5.6e-309 s) the inverse overflows, and 0 times it was NaN. A target too far names
    /// <paramref name="targetName"/>, the parameter the caller's target came from.
    /// </summary>
    internal Vector3d KinematicVelocity(int index, Vector3d target, double duration, string targetName)
    {
        var position = GetPosition(index);
        var difference = target - position;
        if (!difference.IsFinite)
        {
            throw new ArgumentOutOfRangeException(
                targetName,
                target,
                $"The target {target} is so far from particle {index} at {position} that target - x overflows; "
                + "move it in smaller steps.");
        }

        var velocity = difference * (1.0 / duration);
        if (!velocity.IsFinite)
        {
            velocity = difference / duration;
        }

        if (!velocity.IsFinite)
        {
            throw new ArgumentOutOfRangeException(
                nameof(duration),
                duration,
                $"duration {Guard.Format(duration)} s is too short to move particle {index} by {difference}: the "
                + "velocity (target - x) / duration overflows. Give the move a longer duration.");
        }

        return velocity;
    }

    /// <summary>The mass of a particle, in kilograms.</summary>
    public double GetMass(int index)
    {
        Guard.ParticleIndex(index, _count, nameof(index));
        return _masses[index];
    }

    /// <summary>Changes the mass of a particle (a positive finite number of kilograms).</summary>
    public void SetMass(int index, double mass)
    {
        ThrowIfStepping();
        Guard.ParticleIndex(index, _count, nameof(index));
        Guard.Mass(mass, nameof(mass));
        _masses[index] = mass;
        _inverseMasses[index] = _pinned[index] ? 0.0 : 1.0 / mass;
    }

    /// <summary>The radius of a particle, in metres (0 for a point, the default).</summary>
    public double GetRadius(int index)
    {
        Guard.ParticleIndex(index, _count, nameof(index));
        return _radii[index];
    }

    /// <summary>
    /// Gives a particle a radius (a finite number of metres &gt;= 0; 0 makes it a point). Forces do not see it;
    /// contacts (<see cref="IConstraintSet"/> sets such as the contact set) keep its centre that far from colliders and
    /// other particles.
    /// </summary>
    public void SetRadius(int index, double radius)
    {
        ThrowIfStepping();
        Guard.ParticleIndex(index, _count, nameof(index));
        Guard.NonNegativeFinite(radius, nameof(radius));
        _radii[index] = radius;
    }

    /// <summary>True when the particle is pinned (immovable).</summary>
    public bool IsPinned(int index)
    {
        Guard.ParticleIndex(index, _count, nameof(index));
        return _pinned[index];
    }

    /// <summary>
    /// Pins a particle where it is: it gets infinite mass and zero velocity, and no force moves it again (only
    /// <see cref="SetPosition"/>, <see cref="SetVelocity"/> and <see cref="MoveKinematic"/> do). Forces still see it,
    /// so springs pull their other ends toward it.
    /// </summary>
    public void Pin(int index) => Pin(index, Vector3d.Zero);

    /// <summary>
    /// Pins a particle moving at <paramref name="velocity"/>: no force changes that velocity, so it moves along a
    /// straight line, and springs, dampers and drag see its velocity (a moving anchor).
    /// </summary>
    public void Pin(int index, Vector3d velocity)
    {
        ThrowIfStepping();
        Guard.ParticleIndex(index, _count, nameof(index));
        Guard.Finite(velocity, nameof(velocity));
        _pinned[index] = true;
        _inverseMasses[index] = 0.0;
        WriteVelocity(index, velocity);
    }

    /// <summary>
    /// Frees a pinned particle: it moves again under the forces, with its own mass, keeping the velocity it had (a
    /// cloth corner let go by a moving hand flies on with the hand's velocity).
    /// </summary>
    public void Unpin(int index)
    {
        ThrowIfStepping();
        Guard.ParticleIndex(index, _count, nameof(index));
        _pinned[index] = false;
        _inverseMasses[index] = 1.0 / _masses[index];
    }

    /// <summary>
    /// Replaces the whole state vector [positions | velocities]. The values are checked first (all finite): a rejected
    /// call changes nothing. A pinned particle may have a velocity: it then moves at it.
    /// </summary>
    public void SetState(ReadOnlySpan<double> state)
    {
        ThrowIfStepping();
        if (state.Length != Dimension)
        {
            throw new ArgumentException(
                $"state must have 6 values per particle, {Dimension} in all; got {state.Length}.", nameof(state));
        }

        var values = state.ForReading();
        var bad = DoubleChecks.FirstNonFinite(state);
        if (bad >= 0)
        {
            throw new ArgumentException(
                $"state must be finite; value {bad} (particle {(bad % (3 * _count)) / 3}) is {Guard.Format(values[bad])}.",
                nameof(state));
        }

        Compact();
        state.CopyTo(_state);
    }

    /// <summary>Adds a force generator; it acts from the next evaluation on.</summary>
    /// <exception cref="ArgumentException">The generator is already in this system, or names the particles of another one.</exception>
    public void AddForce(IForceGenerator generator)
    {
        ThrowIfStepping();
        Guard.NotNull(generator, nameof(generator));
        if (_forceGenerators.Contains(generator))
        {
            throw new ArgumentException("This force generator is already in the system.", nameof(generator));
        }

        if (generator is IBoundForce { System: { } owner } && !ReferenceEquals(owner, this))
        {
            throw new ArgumentException(
                "This force generator was built for another particle system: its particle indices refer to that one.",
                nameof(generator));
        }

        _forceGenerators.Add(generator);
        _unprojectedStale = true;
        _structureVersion++;
    }

    /// <summary>Removes a force generator; returns false when it was not in the system.</summary>
    public bool RemoveForce(IForceGenerator generator)
    {
        ThrowIfStepping();
        if (!_forceGenerators.Remove(generator))
        {
            return false;
        }

        _ = _finiteDifference.Remove(generator);
        _linearized.Clear(); // a later product must not reach a removed generator; the next Linearize rebuilds it
        _linearizedSource.Clear();
        _unprojectedStale = true;
        _structureVersion++;
        return true;
    }

    /// <summary>Adds a constraint set; the constraint stage applies it from the next step on, after the sets before it.</summary>
    /// <exception cref="ArgumentException">The set is already in this world.</exception>
    public void AddConstraints(IConstraintSet constraints)
    {
        ThrowIfStepping();
        Guard.NotNull(constraints, nameof(constraints));
        if (_constraintSets.Contains(constraints))
        {
            throw new ArgumentException("This constraint set is already in the world.", nameof(constraints));
        }

        _constraintSets.Add(constraints);
        if (constraints is IConstraintForces forces)
        {
            _constraintForces.Add(forces);
            if (constraints is IForceJacobian)
            {
                _structureVersion++; // it enters J: a product needs a Linearize that saw it
            }
        }

        _unprojectedStale = true;
    }

    /// <summary>Removes a constraint set; returns false when it was not in the world.</summary>
    public bool RemoveConstraints(IConstraintSet constraints)
    {
        ThrowIfStepping();
        if (!_constraintSets.Remove(constraints))
        {
            return false;
        }

        if (constraints is IConstraintForces forces)
        {
            _ = _constraintForces.Remove(forces);
            if (constraints is IForceJacobian)
            {
                _linearized.Clear(); // as for a removed generator: no later product may reach it
                _linearizedSource.Clear();
                _structureVersion++;
            }
        }

        _unprojectedStale = true;
        return true;
    }

    /// <summary>
    /// Advances the system by one step of <paramref name="dt"/> seconds with <paramref name="integrator"/>, in stages:
    /// the integrator advances the state under the forces into a scratch buffer; the constraint stage corrects it
    /// (<see cref="IConstraintSet.Resolve"/>, every set in order), except after a position-based integrator
    /// (<see cref="IPositionBasedIntegrator"/>), which has projected every set in its substeps; the result is committed
    /// only if it is finite and its velocities are within <see cref="DivergenceLimit"/>. If any stage throws, the world
    /// is left exactly as it was, and so is an integrator that carries state (<see cref="IStatefulIntegrator"/>): it is
    /// told to commit the state of a committed step and to discard that of a failed one, so a retry takes the same step
    /// as one from a restored snapshot.
    /// </summary>
    /// <exception cref="ArgumentOutOfRangeException">
    /// <paramref name="dt"/> is not a positive finite number, or <see cref="Time"/> + <paramref name="dt"/> is not finite.
    /// </exception>
    /// <exception cref="SimulationDivergedException">
    /// The step produced a value that is not finite, or a velocity beyond <see cref="DivergenceLimit"/>; the system
    /// stays at its last good state and time.
    /// </exception>
    /// <exception cref="InvalidOperationException">
    /// Called from inside this world's own step (a force, a pair filter or a constraint set stepping the world it
    /// belongs to): the nested step would swap the buffers the outer one is writing into. The outer step then fails,
    /// and the world is left as it was.
    /// </exception>
    public void Step(IIntegrator integrator, double dt)
    {
        ThrowIfStepping();
        Guard.NotNull(integrator, nameof(integrator));
        Guard.PositiveFinite(dt, nameof(dt));
        Guard.FiniteEndTime(_time, dt);
        Compact();
        var dimension = 6 * _count;
        if (_next.Length != dimension)
        {
            _next = new double[dimension];
        }

        var current = _state.AsSpan(0, dimension);
        var stateful = integrator as IStatefulIntegrator;
        var committed = false;
        var bracket = _frameDepth == 0;
        if (bracket)
        {
            BeginConstraintSets();
        }

        _stepping = true;
        try
        {
            integrator.Step(this, _time, current, _next, dt);
            if (integrator is not IPositionBasedIntegrator)
            {
                ResolveConstraints(current, dt, integrator is IKickDriftIntegrator);
            }

            _stepping = false;
            CheckDiverged(dt);

            // Commit by swapping the buffers (the spans handed out before the step are documented as stale after it).
            (_state, _next) = (_next, _state);
            _time += dt;
            committed = true;
        }
        finally
        {
            _stepping = false;

            // The integrator's own state follows the world's: kept with a committed step, forgotten with a failed one.
            if (committed)
            {
                stateful?.CommitStep();
            }
            else
            {
                stateful?.DiscardStep();
            }

            if (bracket)
            {
                EndConstraintSets(committed);
            }
        }
    }

    /// <summary>
    /// Opens one all-or-nothing bracket around several steps (a <see cref="Driver.FixedTimestepDriver"/> frame): the
    /// stateful constraint sets (<see cref="IStatefulConstraintSet"/>) keep aside what they show now, and the steps
    /// inside leave them to <see cref="EndFrame"/>.
    /// </summary>
    internal void BeginFrame()
    {
        if (_frameDepth++ == 0)
        {
            BeginConstraintSets();
        }
    }

    /// <summary>Closes the bracket of <see cref="BeginFrame"/>: the sets keep the frame's result, or show again what they showed before it.</summary>
    internal void EndFrame(bool committed)
    {
        if (--_frameDepth == 0)
        {
            EndConstraintSets(committed);
        }
    }

    private void BeginConstraintSets()
    {
        for (var c = 0; c < _constraintSets.Count; c++)
        {
            (_constraintSets[c] as IStatefulConstraintSet)?.BeginStep();
        }
    }

    private void EndConstraintSets(bool committed)
    {
        for (var c = 0; c < _constraintSets.Count; c++)
        {
            if (_constraintSets[c] is IStatefulConstraintSet set)
            {
                if (committed)
                {
                    set.CommitStep();
                }
                else
                {
                    set.DiscardStep();
                }
            }
        }
    }

    /// <summary>
    /// The commit's check of the end state in the scratch buffer: every position finite, every velocity component
    /// within <see cref="DivergenceLimit"/> (one comparison per value; NaN fails it).
    /// </summary>
    private void CheckDiverged(double dt)
    {
        var n = 3 * _count;
        var bad = DoubleChecks.FirstBeyond(_next.AsSpan(0, n), double.MaxValue);
        var velocity = false;
        if (bad < 0)
        {
            bad = DoubleChecks.FirstBeyond(_next.AsSpan(n, n), _divergenceLimit);
            velocity = bad >= 0;
        }

        if (bad < 0)
        {
            return;
        }

        var value = velocity ? _next[n + bad] : _next[bad];
        var particle = bad / 3;
        var axis = "xyz"[bad % 3];
        var cause = DoubleChecks.IsFinite(value)
            ? string.Format(
                CultureInfo.InvariantCulture,
                "particle {0} reached v{1} = {2:R} m/s, beyond the divergence limit {3:R} m/s",
                particle,
                axis,
                value,
                _divergenceLimit)
            : string.Format(
                CultureInfo.InvariantCulture,
                "particle {0}'s {1} {2} is no longer finite ({3})",
                particle,
                velocity ? "velocity" : "position",
                velocity ? "v" + axis : axis.ToString(),
                value);
        throw new SimulationDivergedException(
            _time + dt, _time, velocity ? n + bad : bad, particle, value, _divergenceLimit, cause);
    }

    /// <summary>
    /// The constraint stage after a force-based step: every set corrects the end state in the scratch buffer, told
    /// whether the step was a kick and a drift (<see cref="ConstraintContext.KickDrift"/>).
    /// </summary>
    private void ResolveConstraints(Span<double> start, double dt, bool kickDrift)
    {
        if (_constraintSets.Count == 0)
        {
            return;
        }

        var n = 3 * _count;
        var end = _next.AsSpan(0, 2 * n);
        var context = new ConstraintContext(
            _time, dt, start.Slice(0, n), start.Slice(n, n), end.Slice(0, n), end.Slice(n, n), Masses, InverseMasses, Radii, Runner, kickDrift);
        for (var c = 0; c < _constraintSets.Count; c++)
        {
            _constraintSets[c].Resolve(in context);
        }
    }

    /// <summary>Writes dy/dt = [v | F / m] for the state <paramref name="state"/> at time <paramref name="time"/>.</summary>
    public void Evaluate(double time, ReadOnlySpan<double> state, Span<double> derivative)
    {
        var n = 3 * _count;
        if (state.Length != 2 * n || derivative.Length != 2 * n)
        {
            throw new ArgumentException(
                $"state and derivative must have {2 * n} values; got {state.Length} and {derivative.Length}.");
        }

        var velocities = state.Slice(n, n);
        velocities.CopyTo(derivative);
        ComputeAccelerations(time, state.Slice(0, n), velocities, derivative.Slice(n, n));
    }

    /// <summary>Writes the accelerations F / m (0 for pinned particles) for the given positions and velocities.</summary>
    public void ComputeAccelerations(
        double time, ReadOnlySpan<double> positions, ReadOnlySpan<double> velocities, Span<double> accelerations)
    {
        var n = 3 * _count;
        if (positions.Length != n || velocities.Length != n || accelerations.Length != n)
        {
            throw new ArgumentException(
                $"positions, velocities and accelerations must have {n} values each.");
        }

        _ = AccumulateForces(time, positions, velocities);
        var count = n / 3;
        if (_forces.Length < n || _inverseMasses.Length < count)
        {
            // A generator that added particles while it was evaluated (a step forbids it; a bare Evaluate cannot).
            throw new InvalidOperationException("The world changed while its forces were being evaluated.");
        }

        unsafe
        {
            // The accumulator itself, an array (pinning the read-only span AccumulateForces returns would not bind on
            // Mono). The loop runs over the n values checked above, whatever a generator did to the world meanwhile.
            fixed (double* f = _forces, w = _inverseMasses, a = accelerations)
            {
                for (var i = 0; i < count; i++)
                {
                    var o = 3 * i;
                    a[o] = f[o] * w[i];
                    a[o + 1] = f[o + 1] * w[i];
                    a[o + 2] = f[o + 2] * w[i];
                }
            }
        }
    }

    /// <summary>
    /// Clears the force accumulator and lets every generator add into it, for the given positions and velocities, then
    /// every constraint set that acts through forces (<see cref="IConstraintForces"/>: rods, taut cables) adds its
    /// constraint forces for those applied forces. Returns the accumulator (3 values per particle), valid until the next
    /// evaluation.
    /// </summary>
    public ReadOnlySpan<double> AccumulateForces(double time, ReadOnlySpan<double> positions, ReadOnlySpan<double> velocities)
    {
        var n = 3 * _count;
        var forces = _forces.AsSpan(0, n);
        forces.Clear();
        var view = new ParticleState(time, positions, velocities, Masses, InverseMasses, Runner);
        for (var g = 0; g < _forceGenerators.Count; g++)
        {
            _forceGenerators[g].AddForces(in view, forces);
        }

        for (var c = 0; c < _constraintForces.Count; c++)
        {
            _constraintForces[c].AddConstraintForces(in view, forces);
        }

        return forces;
    }

    /// <inheritdoc />
    void IPositionBasedSystem.ComputeUnprojectedAccelerations(
        double time, ReadOnlySpan<double> positions, ReadOnlySpan<double> velocities, Span<double> accelerations)
    {
        var n = 3 * _count;
        if (positions.Length != n || velocities.Length != n || accelerations.Length != n)
        {
            throw new ArgumentException($"positions, velocities and accelerations must have {n} values each.");
        }

        if (_unprojectedStale)
        {
            CollectUnprojected();
        }

        var forces = _forces.AsSpan(0, n);
        forces.Clear();
        var view = new ParticleState(time, positions, velocities, Masses, InverseMasses, Runner);
        for (var g = 0; g < _unprojected.Count; g++)
        {
            _unprojected[g].AddForces(in view, forces);
        }

        unsafe
        {
            // The accumulator and the inverse masses are arrays of at least n and n / 3 values, accelerations n. The
            // bound is n / 3, not _count: a force that added a particle during a bare call (outside a step, where the
            // world cannot refuse it) would otherwise make the loop write past the accelerations.
            var count = n / 3;
            fixed (double* f = _forces, w = _inverseMasses, a = accelerations)
            {
                double* fi = f, ai = a;
                for (var i = 0; i < count; i++, fi += 3, ai += 3)
                {
                    var wi = w[i];
                    ai[0] = fi[0] * wi;
                    ai[1] = fi[1] * wi;
                    ai[2] = fi[2] * wi;
                }
            }
        }
    }

    /// <inheritdoc />
    void IPositionBasedSystem.ProjectConstraints(
        double time,
        double dt,
        ReadOnlySpan<double> startPositions,
        ReadOnlySpan<double> startVelocities,
        Span<double> positions,
        Span<double> velocities)
    {
        var context = SubstepContext(time, dt, startPositions, startVelocities, positions, velocities);
        for (var c = 0; c < _constraintSets.Count; c++)
        {
            _constraintSets[c].Project(in context);
        }
    }

    /// <inheritdoc />
    void IPositionBasedSystem.SolveConstraintVelocities(
        double time,
        double dt,
        ReadOnlySpan<double> startPositions,
        ReadOnlySpan<double> startVelocities,
        Span<double> positions,
        Span<double> velocities)
    {
        var context = SubstepContext(time, dt, startPositions, startVelocities, positions, velocities);
        for (var c = 0; c < _constraintSets.Count; c++)
        {
            _constraintSets[c].SolveVelocities(in context);
        }
    }

    private ConstraintContext SubstepContext(
        double time,
        double dt,
        ReadOnlySpan<double> startPositions,
        ReadOnlySpan<double> startVelocities,
        Span<double> positions,
        Span<double> velocities)
    {
        Guard.PositiveFinite(dt, nameof(dt));
        return new ConstraintContext(
            time, dt, startPositions, startVelocities, positions, velocities, Masses, InverseMasses, Radii, Runner);
    }

    /// <summary>The generators that no constraint set projects (<see cref="IForceProjection"/>), in their order.</summary>
    private void CollectUnprojected()
    {
        _unprojected.Clear();
        for (var g = 0; g < _forceGenerators.Count; g++)
        {
            var generator = _forceGenerators[g];
            var projected = false;
            for (var c = 0; c < _constraintSets.Count && !projected; c++)
            {
                projected = _constraintSets[c] is IForceProjection projection
                    && ReferenceEquals(projection.Force, generator);
            }

            if (!projected)
            {
                _unprojected.Add(generator);
            }
        }

        _unprojectedStale = false;
    }

    /// <inheritdoc />
    /// <remarks>
    /// Linearises every generator that implements <see cref="IForceJacobian"/>, in the order they were added; the
    /// others enter J by finite differences when <paramref name="userForces"/> asks for it, and not at all otherwise
    /// (they then act on the step explicitly, through <see cref="AccumulateForces"/>).
    /// </remarks>
    void ILinearizableSystem.Linearize(
        double time,
        ReadOnlySpan<double> positions,
        ReadOnlySpan<double> velocities,
        double positionScale,
        double velocityScale,
        UserForceTreatment userForces,
        Span<double> positionJacobianTimesVelocity)
    {
        CheckLinearization(positions.Length, velocities.Length, positionJacobianTimesVelocity.Length);
        CollectLinearized(userForces);
        if (_linearized.Count > 0 && _linearizedSource[_linearized.Count - 1] >= _forceGenerators.Count)
        {
            // A constraint set linearises the multipliers of its last forces: evaluate them at this state first.
            _ = AccumulateForces(time, positions, velocities);
        }

        var view = new ParticleState(time, positions, velocities, Masses, InverseMasses, Runner);
        for (var j = 0; j < _linearized.Count; j++)
        {
            _linearized[j].Linearize(view, positionScale, velocityScale, positionJacobianTimesVelocity);
        }

        _linearizedVersion = _structureVersion;
    }

    /// <inheritdoc />
    /// <remarks>
    /// Each generator in the order they were added: one that implements <see cref="IForceLinearization"/> in one pass,
    /// the others by AddForces, then (when they enter J: <see cref="IForceJacobian"/>, or finite differences when
    /// <paramref name="userForces"/> asks for it) Linearize and AddDiagonalBlocks; then the constraint forces. The
    /// forces, (df/dx) v and the blocks are separate accumulators, each receiving the generators' terms in the same
    /// order as the three separate calls, so the results are theirs to the last bit.
    /// </remarks>
    ReadOnlySpan<double> ILinearizableSystem.AccumulateForcesAndLinearize(
        double time,
        ReadOnlySpan<double> positions,
        ReadOnlySpan<double> velocities,
        double positionScale,
        double velocityScale,
        UserForceTreatment userForces,
        Span<double> positionJacobianTimesVelocity,
        Span<double> diagonalBlocks)
    {
        CheckLinearization(positions.Length, velocities.Length, positionJacobianTimesVelocity.Length);
        if (diagonalBlocks.Length < 9 * _count)
        {
            throw new ArgumentException(
                $"diagonalBlocks must hold 9 values per particle, {9 * _count}; it holds {diagonalBlocks.Length}.", nameof(diagonalBlocks));
        }

        CollectLinearized(userForces);
        var n = 3 * _count;
        var forces = _forces.AsSpan(0, n);
        forces.Clear();
        var view = new ParticleState(time, positions, velocities, Masses, InverseMasses, Runner);
        var next = 0; // the next entry of _linearized: the generators' own Jacobians and wrappers, in generator order
        for (var g = 0; g < _forceGenerators.Count; g++)
        {
            var generator = _forceGenerators[g];
            var jacobian = next < _linearized.Count && _linearizedSource[next] == g ? _linearized[next++] : null;
            if (jacobian is IForceLinearization fused && ReferenceEquals(fused, generator))
            {
                fused.AddForcesAndLinearize(in view, positionScale, velocityScale, forces, positionJacobianTimesVelocity, diagonalBlocks);
                continue;
            }

            generator.AddForces(in view, forces);
            if (jacobian is not null)
            {
                jacobian.Linearize(view, positionScale, velocityScale, positionJacobianTimesVelocity);
                jacobian.AddDiagonalBlocks(diagonalBlocks);
            }
        }

        for (var c = 0; c < _constraintForces.Count; c++)
        {
            _constraintForces[c].AddConstraintForces(in view, forces);
            if (next < _linearized.Count && _linearizedSource[next] == _forceGenerators.Count + c)
            {
                // Right after its forces at this state: a constraint set linearises the multipliers it just solved for.
                var jacobian = _linearized[next++];
                jacobian.Linearize(view, positionScale, velocityScale, positionJacobianTimesVelocity);
                jacobian.AddDiagonalBlocks(diagonalBlocks);
            }
        }

        _linearizedVersion = _structureVersion;
        return forces;
    }

    /// <summary>Checks the buffers of a linearisation against the world's size.</summary>
    private void CheckLinearization(int positions, int velocities, int positionJacobianTimesVelocity)
    {
        var n = 3 * _count;
        if (positions != n || velocities != n || positionJacobianTimesVelocity != n)
        {
            throw new ArgumentException(
                $"positions, velocities and positionJacobianTimesVelocity must have {n} values each; got "
                + $"{positions}, {velocities} and {positionJacobianTimesVelocity}.");
        }
    }

    /// <summary>
    /// The generators that enter J, in the order they were added: those that implement <see cref="IForceJacobian"/>,
    /// and the others wrapped in finite differences when <paramref name="userForces"/> asks for it; then the constraint
    /// sets that act through forces (<see cref="IConstraintForces"/>) and implement <see cref="IForceJacobian"/>.
    /// </summary>
    private void CollectLinearized(UserForceTreatment userForces)
    {
        _linearizedVersion = -1;
        _linearized.Clear();
        _linearizedSource.Clear();
        for (var g = 0; g < _forceGenerators.Count; g++)
        {
            var generator = _forceGenerators[g];
            if (generator is IForceJacobian jacobian)
            {
                _linearized.Add(jacobian);
                _linearizedSource.Add(g);
            }
            else if (userForces == UserForceTreatment.FiniteDifference)
            {
                if (!_finiteDifference.TryGetValue(generator, out var wrapper))
                {
                    wrapper = new FiniteDifferenceJacobian(generator);
                    _finiteDifference.Add(generator, wrapper);
                }

                _linearized.Add(wrapper);
                _linearizedSource.Add(g);
            }
        }

        // Then the constraint sets that act through forces and linearise them (rods: their tensions' geometric
        // stiffness), numbered after the generators.
        for (var c = 0; c < _constraintForces.Count; c++)
        {
            if (_constraintForces[c] is IForceJacobian jacobian)
            {
                _linearized.Add(jacobian);
                _linearizedSource.Add(_forceGenerators.Count + c);
            }
        }
    }

    /// <inheritdoc />
    /// <exception cref="InvalidOperationException">
    /// No Linearize yet, or particles or generators were added or removed since the last one.
    /// </exception>
    void ILinearizableSystem.AddJacobianProduct(ReadOnlySpan<double> w, Span<double> result)
    {
        CheckLinearized(w.Length, result.Length, 3);
        for (var j = 0; j < _linearized.Count; j++)
        {
            _linearized[j].AddJacobianProduct(w, result);
        }
    }

    /// <inheritdoc />
    bool IJacobianProductTail.TryGetUniformTail(out double coefficient)
    {
        var tail = UniformTail(out coefficient);
        return tail >= 0;
    }

    /// <inheritdoc />
    /// <exception cref="InvalidOperationException">
    /// No Linearize yet, or particles or generators were added or removed since the last one, or no uniform tail.
    /// </exception>
    void IJacobianProductTail.AddJacobianProductBeforeTail(ReadOnlySpan<double> w, Span<double> result)
    {
        CheckLinearized(w.Length, result.Length, 3);
        var tail = UniformTail(out _);
        if (tail < 0)
        {
            throw new InvalidOperationException("The world's Jacobian product has no uniform tail: use AddJacobianProduct.");
        }

        for (var j = 0; j < tail; j++)
        {
            _linearized[j].AddJacobianProduct(w, result);
        }
    }

    /// <summary>
    /// The index among the linearised generators of the last one whose product does anything, when that product is
    /// c w on every coordinate (with <paramref name="coefficient"/> c), else -1. The generators after it add nothing.
    /// </summary>
    private int UniformTail(out double coefficient)
    {
        coefficient = 0.0;
        if (_linearizedVersion != _structureVersion)
        {
            return -1;
        }

        // Bounded by the generators; the first from the end that is not a product of nothing decides.
        for (var j = _linearized.Count - 1; j >= 0; j--)
        {
            if (_linearized[j] is not IUniformJacobianProduct uniform || !uniform.TryGetUniformProduct(out var c, out var none))
            {
                return -1;
            }

            if (!none)
            {
                coefficient = c;
                return j;
            }
        }

        return -1;
    }

    /// <inheritdoc />
    /// <exception cref="InvalidOperationException">
    /// No Linearize yet, or particles or generators were added or removed since the last one.
    /// </exception>
    void ILinearizableSystem.AddDiagonalBlocks(Span<double> blocks)
    {
        CheckLinearized(blocks.Length, blocks.Length, 9);
        for (var j = 0; j < _linearized.Count; j++)
        {
            _linearized[j].AddDiagonalBlocks(blocks);
        }
    }

    /// <inheritdoc />
    /// <remarks>The couplings of the linearised generators that state theirs (<see cref="IJacobianCouplings"/>), in order.</remarks>
    int ILinearizableSystem.CouplingCount
    {
        get
        {
            var count = 0;
            for (var j = 0; j < _linearized.Count; j++)
            {
                if (_linearized[j] is IJacobianCouplings couplings)
                {
                    count += couplings.CouplingCount;
                }
            }

            return count;
        }
    }

    /// <inheritdoc />
    /// <remarks>
    /// The revision is the world's number among the process's worlds (high 32 bits) and its structure version, which
    /// every added or removed force and particle changes (low 32 bits); the forces are those of the last
    /// linearisation, as for <see cref="ILinearizableSystem.CouplingCount"/>.
    /// </remarks>
    bool ICouplingRevision.TryGetCouplingRevision(out long revision)
    {
        revision = (_worldNumber << 32) | (uint)_structureVersion;
        for (var j = 0; j < _linearized.Count; j++)
        {
            if (_linearized[j] is IJacobianCouplings and not IAppendOnlyCouplings)
            {
                return false;
            }
        }

        return true;
    }

    /// <inheritdoc />
    void ILinearizableSystem.WriteCouplings(Span<int> first, Span<int> second)
    {
        var offset = 0;
        for (var j = 0; j < _linearized.Count; j++)
        {
            if (_linearized[j] is IJacobianCouplings couplings)
            {
                var count = couplings.CouplingCount;
                couplings.WriteCouplings(first.Slice(offset, count), second.Slice(offset, count));
                offset += count;
            }
        }
    }

    /// <inheritdoc />
    void ILinearizableSystem.AddCouplingBlocks(Span<double> destination, ReadOnlySpan<int> forwardBlock, ReadOnlySpan<int> backwardBlock)
    {
        var offset = 0;
        for (var j = 0; j < _linearized.Count; j++)
        {
            if (_linearized[j] is IJacobianCouplings couplings)
            {
                var count = couplings.CouplingCount;
                couplings.AddCouplingBlocks(destination, forwardBlock.Slice(offset, count), backwardBlock.Slice(offset, count));
                offset += count;
            }
        }
    }

    /// <summary>A view of the committed state for force generators and diagnostics.</summary>
    public ParticleState View() => new(_time, Positions, Velocities, Masses, InverseMasses);

    /// <summary>The total kinetic energy, sum of m v^2 / 2 over the particles, in joules.</summary>
    public double KineticEnergy()
    {
        var v = Velocities.ForReading();
        var sum = 0.0;
        for (var i = 0; i < _count; i++)
        {
            var o = 3 * i;
            sum += 0.5 * _masses[i] * ((v[o] * v[o]) + (v[o + 1] * v[o + 1]) + (v[o + 2] * v[o + 2]));
        }

        return sum;
    }

    /// <summary>The sum of the potential energies of the generators that report one (<see cref="IPotentialEnergy"/>), in joules.</summary>
    public double PotentialEnergy()
    {
        var view = View();
        var sum = 0.0;
        foreach (var generator in _forceGenerators)
        {
            if (generator is IPotentialEnergy potential)
            {
                sum += potential.PotentialEnergy(in view);
            }
        }

        return sum;
    }

    /// <summary>The total linear momentum, sum of m v over the particles (pinned particles have v = 0).</summary>
    public Vector3d TotalMomentum()
    {
        var v = Velocities.ForReading();
        double px = 0, py = 0, pz = 0;
        for (var i = 0; i < _count; i++)
        {
            var o = 3 * i;
            px += _masses[i] * v[o];
            py += _masses[i] * v[o + 1];
            pz += _masses[i] * v[o + 2];
        }

        return new Vector3d(px, py, pz);
    }

    /// <summary>
    /// Writes the positions, rounded to single precision, into <paramref name="destination"/> (one vector per
    /// particle): the layout a renderer's vertex buffer takes. Allocates nothing.
    /// </summary>
    public void CopyPositionsTo(Span<Vector3> destination)
    {
        if (destination.Length < _count)
        {
            throw new ArgumentException(
                $"destination must hold at least {_count} vectors; it holds {destination.Length}.", nameof(destination));
        }

        var x = Positions.ForReading();
        for (var i = 0; i < _count; i++)
        {
            destination[i] = new Vector3((float)x[3 * i], (float)x[(3 * i) + 1], (float)x[(3 * i) + 2]);
        }
    }

    private void CheckLinearized(int input, int output, int perParticle)
    {
        if (_linearizedVersion != _structureVersion)
        {
            throw new InvalidOperationException(_linearizedVersion < 0
                ? "Jacobian products and blocks need a Linearize of the world first."
                : "Particles or force generators were added or removed since the last Linearize: linearise again.");
        }

        var needed = perParticle * _count;
        if (input != needed || output != needed)
        {
            throw new ArgumentException($"The buffers must hold {needed} values ({perParticle} per particle); got {input} and {output}.");
        }
    }

    /// <summary>
    /// Throws when called from inside this world's own step (by a force generator, a pair filter or a constraint set):
    /// every change to the world, a nested step of it, and its driver's frames and resets.
    /// </summary>
    internal void ThrowIfStepping()
    {
        if (_stepping)
        {
            throw new InvalidOperationException(
                "The world cannot be changed or stepped during its own step (from a force generator, a pair filter or "
                + "a constraint set): a step either commits whole or leaves the world as it was.");
        }
    }

    private void WritePosition(int index, Vector3d p)
    {
        var o = 3 * index;
        _state[o] = p.X;
        _state[o + 1] = p.Y;
        _state[o + 2] = p.Z;
    }

    private void WriteVelocity(int index, Vector3d v)
    {
        var o = (3 * _capacity) + (3 * index);
        _state[o] = v.X;
        _state[o + 1] = v.Y;
        _state[o + 2] = v.Z;
    }

    /// <summary>Drops the spare capacity so that the state is exactly 6 N contiguous values.</summary>
    private void Compact()
    {
        if (_capacity != _count)
        {
            Reallocate(_count);
        }
    }

    private void Reallocate(int capacity)
    {
        var state = new double[6 * capacity];
        Array.Copy(_state, 0, state, 0, 3 * _count);
        Array.Copy(_state, 3 * _capacity, state, 3 * capacity, 3 * _count);
        _state = state;
        Array.Resize(ref _masses, capacity);
        Array.Resize(ref _inverseMasses, capacity);
        Array.Resize(ref _pinned, capacity);
        Array.Resize(ref _radii, capacity);
        Array.Resize(ref _forces, 3 * capacity);
        _capacity = capacity;
    }
}
