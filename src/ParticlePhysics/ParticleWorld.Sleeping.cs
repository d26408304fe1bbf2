using System;

namespace ParticlePhysics;

// Sleeping: particles and bodies that stay slow stop moving and stop costing their pairs and projections until
// something meets them, moves them or changes a force (docs/architecture.md, "Sleeping").
public sealed partial class ParticleWorld
{
    /// <summary>The default <see cref="SleepTime"/>: half a second, as Box2D's.</summary>
    public const double DefaultSleepTime = 0.5;

    private double _sleepSpeed;
    private double _sleepTime = DefaultSleepTime;
    private bool[] _asleep = Array.Empty<bool>();
    private double[] _calm = Array.Empty<double>(); // how long each awake particle has been slower than the sleep speed
    private bool[] _moving = Array.Empty<bool>(); // moved faster than the sleep speed in the last step: wakes what it touches
    private bool[] _fresh = Array.Empty<bool>(); // woken, added or set by the host since the last step: its velocity is news
    private int[] _sleepNext = Array.Empty<int>(); // each sleeping island as a ring, for waking it whole
    private int[] _woken = Array.Empty<int>(); // the particles this step woke, put back to sleep if the step fails
    private int _wokenCount;
    private bool _recordWakes;
    private int _sleepingCount;
    private int _linkRevision;
    private readonly ParticleIslands _islands = new();
    private double[] _islandCalm = Array.Empty<double>();
    private int[] _islandHead = Array.Empty<int>();
    private int[] _islandTail = Array.Empty<int>();
    private SleepSnapshot? _frameSleep;
    private SleepView? _sleepView;

    /// <summary>
    /// The speed, in m/s, below which a particle counts as at rest for sleeping (its move over a step divided by the
    /// step); 0 (the default) turns sleeping off.
    /// </summary>
    /// <remarks>
    /// An island (a particle alone, or the particles a body ties together) whose particles all stay below this speed
    /// for <see cref="SleepTime"/> falls asleep at the end of a step: its velocities become 0 and its particles stop
    /// moving, as if pinned, until it is woken. A particle that moved faster than this in its last step and touches it,
    /// or one just woken, added or set that meets it faster, wakes the island in the same substep, before the contact
    /// is projected, so the impact meets the island's own masses; so do a collider moving into it, <see cref="Wake"/>,
    /// and anything that changes a particle (its position, velocity, mass, radius or pin), the world's state, its forces
    /// or constraint sets, or a generator's or set's parameters (<see cref="IParticleLinks.Revision"/>). Sleeping works with xpbd, and only
    /// while every force generator and constraint set of the world implements <see cref="IParticleLinks"/> (gravity,
    /// linear drag, contact sets and shape matching do); otherwise every particle stays awake. Islands are found in
    /// index order on one thread, so sleeping keeps a run's bits the same on one core or many.
    /// </remarks>
    public double SleepSpeed
    {
        get => _sleepSpeed;
        set
        {
            ThrowIfStepping();
            if (!(value >= 0.0) || double.IsInfinity(value))
            {
                throw new ArgumentOutOfRangeException(
                    nameof(SleepSpeed), value, $"SleepSpeed must be a finite speed >= 0 m/s (0 turns sleeping off); got {Guard.Format(value)}.");
            }

            _sleepSpeed = value;
            if (value == 0.0)
            {
                WakeAll();
            }
        }
    }

    /// <summary>How long, in seconds, an island must stay below <see cref="SleepSpeed"/> to fall asleep (default 0.5 s).</summary>
    public double SleepTime
    {
        get => _sleepTime;
        set
        {
            ThrowIfStepping();
            if (!(value > 0.0) || double.IsInfinity(value))
            {
                throw new ArgumentOutOfRangeException(
                    nameof(SleepTime), value, $"SleepTime must be a finite time > 0 s; got {Guard.Format(value)}.");
            }

            _sleepTime = value;
        }
    }

    /// <summary>How many particles sleep.</summary>
    public int SleepingCount => _sleepingCount;

    /// <summary>Whether a particle sleeps (<see cref="SleepSpeed"/>).</summary>
    public bool IsAsleep(int index)
    {
        Guard.ParticleIndex(index, _count, nameof(index));
        return _asleep[index];
    }

    /// <summary>Wakes a particle and the island it sleeps with; nothing if it is awake.</summary>
    public void Wake(int index)
    {
        ThrowIfStepping();
        Guard.ParticleIndex(index, _count, nameof(index));
        WakeIsland(index);
    }

    /// <summary>Wakes every particle.</summary>
    public void WakeAll()
    {
        for (var i = 0; i < _count && _sleepingCount > 0; i++)
        {
            WakeIsland(i);
        }
    }

    private void WakeIsland(int index)
    {
        if (!_asleep[index])
        {
            return;
        }

        // The ring is left as it is: a failed step puts the same island back to sleep.
        var i = index;
        do
        {
            _asleep[i] = false;
            _inverseMasses[i] = _pinned[i] ? 0.0 : 1.0 / _masses[i];
            _calm[i] = 0.0;
            _fresh[i] = true;
            _sleepingCount--;
            if (_recordWakes)
            {
                _woken[_wokenCount++] = i;
            }

            i = _sleepNext[i];
        }
        while (i != index);
    }

    /// <summary>Before a step: whether sleeping can act in it; wakes everything if a generator or set changed.</summary>
    private bool BeginSleep(bool positionBased)
    {
        _wokenCount = 0;
        _recordWakes = true;
        if (_sleepSpeed == 0.0 || !positionBased || !LinkRevision(out var revision))
        {
            WakeAll();
            return false;
        }

        if (revision != _linkRevision)
        {
            WakeAll();
            _linkRevision = revision;
        }

        return true;
    }

    /// <summary>After a failed step: the particles it woke sleep again, as they did before it.</summary>
    private void UndoWakes()
    {
        for (var k = 0; k < _wokenCount; k++)
        {
            var i = _woken[k];
            _asleep[i] = true;
            _inverseMasses[i] = 0.0;
            _sleepingCount++;
        }

        _wokenCount = 0;
        _recordWakes = false;
    }

    /// <summary>A hash of the generators' and sets' count and revisions; false if one of them cannot tell its links.</summary>
    private bool LinkRevision(out int revision)
    {
        revision = _forceGenerators.Count + (31 * _constraintSets.Count);
        for (var g = 0; g < _forceGenerators.Count; g++)
        {
            if (_forceGenerators[g] is not IParticleLinks links)
            {
                return false;
            }

            revision = unchecked((revision * 31) + links.Revision);
        }

        for (var c = 0; c < _constraintSets.Count; c++)
        {
            if (_constraintSets[c] is not IParticleLinks links)
            {
                return false;
            }

            revision = unchecked((revision * 31) + links.Revision);
        }

        return true;
    }

    /// <summary>
    /// After a committed step: the islands of this step's links, each awake particle's calm time, and the islands
    /// whose every awake particle has been calm for the sleep time put to sleep.
    /// </summary>
    private void UpdateSleep(double dt)
    {
        _recordWakes = false;
        var n = _count;
        _islands.Reset(n, _pinned);
        for (var g = 0; g < _forceGenerators.Count; g++)
        {
            ((IParticleLinks)_forceGenerators[g]).AddLinks(_islands);
        }

        for (var c = 0; c < _constraintSets.Count; c++)
        {
            ((IParticleLinks)_constraintSets[c]).AddLinks(_islands);
        }

        for (var i = 0; i < n; i++)
        {
            if (_asleep[i])
            {
                _islands.Link(i, _sleepNext[i]); // the island it sleeps in, whose particles need not touch this step
            }
        }

        // The speed is the step's move over dt, not the velocity: a grain held by its contacts can carry a velocity
        // that its position never realises (the velocity pass's single sweep), and would keep its pile awake forever.
        var velocities = _state.AsSpan(3 * _capacity, 3 * n);
        var positions = _state.AsSpan(0, 3 * n);
        var previous = _next.AsSpan(0, 3 * n); // the state before the step (the buffers were swapped at the commit)
        var limit = _sleepSpeed * dt * _sleepSpeed * dt;
        for (var i = 0; i < n; i++)
        {
            _islandCalm[i] = double.PositiveInfinity;
            _islandHead[i] = -1;
            if (_asleep[i])
            {
                continue;
            }

            var o = 3 * i;
            double dx = positions[o] - previous[o], dy = positions[o + 1] - previous[o + 1], dz = positions[o + 2] - previous[o + 2];
            _moving[i] = !((dx * dx) + (dy * dy) + (dz * dz) < limit);
            _fresh[i] = false;
            _calm[i] = _moving[i] ? 0.0 : _calm[i] + dt;
        }

        // An island sleeps when it has an awake particle (its least calm time is then finite) and none has been calm
        // for less than the sleep time.
        for (var i = 0; i < n; i++)
        {
            if (!_pinned[i] && !_asleep[i])
            {
                var root = _islands.Find(i);
                _islandCalm[root] = Math.Min(_islandCalm[root], _calm[i]);
            }
        }

        for (var i = 0; i < n; i++)
        {
            if (_pinned[i])
            {
                continue;
            }

            var root = _islands.Find(i);
            var calm = _islandCalm[root];
            if (double.IsPositiveInfinity(calm) || !(calm >= _sleepTime))
            {
                continue;
            }

            // Chained in index order into the island's ring, its head and tail kept at the root.
            if (_islandHead[root] < 0)
            {
                _islandHead[root] = i;
            }
            else
            {
                _sleepNext[_islandTail[root]] = i;
            }

            _islandTail[root] = i;
            if (!_asleep[i])
            {
                _asleep[i] = true;
                _sleepingCount++;
            }

            _inverseMasses[i] = 0.0;
            velocities[3 * i] = 0.0;
            velocities[(3 * i) + 1] = 0.0;
            velocities[(3 * i) + 2] = 0.0;
        }

        for (var i = 0; i < n; i++)
        {
            if (!_pinned[i] && _islandHead[i] >= 0)
            {
                _sleepNext[_islandTail[i]] = _islandHead[i];
            }
        }
    }

    /// <summary>The context's view of sleeping, or null while no particle can sleep.</summary>
    private ISleepingParticles? SleepingForContext(bool active) => active ? _sleepView ??= new SleepView(this) : null;

    private void ResizeSleep(int capacity)
    {
        Array.Resize(ref _asleep, capacity);
        Array.Resize(ref _calm, capacity);
        Array.Resize(ref _moving, capacity);
        Array.Resize(ref _fresh, capacity);
        Array.Resize(ref _sleepNext, capacity);
        Array.Resize(ref _woken, capacity);
        Array.Resize(ref _islandCalm, capacity);
        Array.Resize(ref _islandHead, capacity);
        Array.Resize(ref _islandTail, capacity);
    }

    /// <summary>At a frame's start: what sleeps, so that a failed frame puts it back.</summary>
    private void SaveSleep()
    {
        if (_sleepSpeed == 0.0 && _sleepingCount == 0)
        {
            _frameSleep?.Clear();
            return;
        }

        (_frameSleep ??= new SleepSnapshot()).Save(_asleep, _calm, _sleepNext, _moving, _fresh, _count, _sleepingCount, _linkRevision);
    }

    /// <summary>After a failed frame (whose rewind woke everything): the sleep of the frame's start.</summary>
    private void RestoreSleep()
    {
        if (_frameSleep is not { Saved: true } saved || saved.Count != _count)
        {
            return;
        }

        _sleepingCount = saved.Restore(_asleep, _calm, _sleepNext, _moving, _fresh, out _linkRevision);
        for (var i = 0; i < _count; i++)
        {
            if (_asleep[i])
            {
                _inverseMasses[i] = 0.0;
            }
        }
    }

    private sealed class SleepView : ISleepingParticles
    {
        private readonly ParticleWorld _world;

        public SleepView(ParticleWorld world)
        {
            _world = world;
        }

        public double WakeSpeed => _world._sleepSpeed;

        public bool IsAsleep(int particle) => (uint)particle < (uint)_world._count && _world._asleep[particle];

        public bool MovedLastStep(int particle) => (uint)particle < (uint)_world._count && _world._moving[particle];

        public bool IsFresh(int particle) => (uint)particle < (uint)_world._count && _world._fresh[particle];

        public void Wake(int particle)
        {
            if ((uint)particle < (uint)_world._count)
            {
                _world.WakeIsland(particle);
            }
        }
    }

    private sealed class SleepSnapshot
    {
        private bool[] _asleep = Array.Empty<bool>();
        private double[] _calm = Array.Empty<double>();
        private int[] _next = Array.Empty<int>();
        private bool[] _moving = Array.Empty<bool>();
        private bool[] _fresh = Array.Empty<bool>();
        private int _sleeping;
        private int _revision;

        public bool Saved { get; private set; }

        public int Count { get; private set; }

        public void Clear() => Saved = false;

        public void Save(bool[] asleep, double[] calm, int[] next, bool[] moving, bool[] fresh, int count, int sleeping, int revision)
        {
            if (_asleep.Length < count)
            {
                _asleep = new bool[count];
                _calm = new double[count];
                _next = new int[count];
                _moving = new bool[count];
                _fresh = new bool[count];
            }

            Array.Copy(asleep, _asleep, count);
            Array.Copy(calm, _calm, count);
            Array.Copy(next, _next, count);
            Array.Copy(moving, _moving, count);
            Array.Copy(fresh, _fresh, count);
            Count = count;
            _sleeping = sleeping;
            _revision = revision;
            Saved = true;
        }

        public int Restore(bool[] asleep, double[] calm, int[] next, bool[] moving, bool[] fresh, out int revision)
        {
            Array.Copy(_asleep, asleep, Count);
            Array.Copy(_calm, calm, Count);
            Array.Copy(_next, next, Count);
            Array.Copy(_moving, moving, Count);
            Array.Copy(_fresh, fresh, Count);
            revision = _revision;
            return _sleeping;
        }
    }
}
