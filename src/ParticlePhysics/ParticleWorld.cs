using System;
using System.Collections.Generic;
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
public sealed partial class ParticleWorld
{
    private double[] _state = Array.Empty<double>();
    private double[] _masses = Array.Empty<double>();
    private double[] _inverseMasses = Array.Empty<double>();
    private bool[] _pinned = Array.Empty<bool>();
    private double[] _radii = Array.Empty<double>();
    private double[] _forces = Array.Empty<double>();
    private double[] _next = Array.Empty<double>();
    private int _capacity;
    private int _count;
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

    /// <summary>The positions, 3 values per particle (x0, y0, z0, x1, ...). Valid until the system next changes.</summary>
    public ReadOnlySpan<double> Positions => _state.AsSpan(0, 3 * _count);

    /// <summary>The velocities, 3 values per particle. Valid until the system next changes.</summary>
    public ReadOnlySpan<double> Velocities => _state.AsSpan(3 * _capacity, 3 * _count);

    /// <summary>The masses, one per particle (a pinned particle keeps its mass; it is its inverse that is 0).</summary>
    public ReadOnlySpan<double> Masses => _masses.AsSpan(0, _count);

    /// <summary>The inverse masses, one per particle: 1 / m, or 0 for a pinned or a sleeping particle (<see cref="SleepSpeed"/>).</summary>
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
        _asleep[index] = false;
        _calm[index] = 0.0;
        _moving[index] = false;
        _fresh[index] = true; // new: its velocity may wake what it meets
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
        WakeIsland(index);
        _fresh[index] = true;
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
        WakeIsland(index);
        _fresh[index] = true;
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
    /// 1 / duration (the bits the golden hashes hold), and divided instead where that is not finite: below
    /// 1 / double.MaxValue (about 5.6e-309 s) the inverse overflows, and 0 times it would be NaN. A target too far names
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
        WakeIsland(index);
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
        WakeIsland(index);
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
        WakeIsland(index);
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
        WakeIsland(index);
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
        WakeAll();
        state.CopyTo(_state);
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
        ResizeSleep(capacity);
        _capacity = capacity;
    }
}
