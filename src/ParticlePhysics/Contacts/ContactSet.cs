using System;
using System.Collections.Generic;
using System.Runtime.CompilerServices;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Contacts;

/// <summary>
/// Contacts as a stage of the step (<see cref="IConstraintSet"/>): particles against obstacles (planes, spheres,
/// capsules, boxes) and, if <see cref="ParticleCollisions"/> is on, against each other, resolved with impulses at the
/// time each impact happens within the step.
/// </summary>
/// <remarks>
/// <para>
/// The contract's rules: an impact at normal relative speed u leaves at e u (e: restitution) and loses
/// min(|tangential velocity|, mu (1 + e) u) of its tangential velocity (mu: Coulomb friction as an impulse); an impact
/// whose rebound e u is below <see cref="RestingSpeed"/> does not bounce but rests, held by the normal force N, and
/// slides with friction mu N until it stops. Between particles the impulse acts along the line of centres and conserves
/// momentum; two particles at exactly the same point (spawned there) separate along a direction taken from their
/// indices (<see cref="PairNormal"/>), so that a heap spawned at one point opens in every direction.
/// </para>
/// <para>
/// After a force-based integrator (<see cref="Resolve"/>), in stages: (1) each particle's path within the step is the
/// cubic through its start and end (<see cref="ParticlePaths"/>: exact for constant forces); (2) the broad phase
/// (<see cref="SpatialHashGrid"/>) pairs the particles whose swept boxes overlap, listed in the order of its cells when
/// they fill a box (the order every later stage walks the pairs in, so that a particle's pairs come close together);
/// (3) impacts are found by safe steps along the paths (<see cref="ContactSearch"/>) and resolved in time order
/// (<see cref="ImpactQueue"/>), each impulse changing the rest of its particles' paths; (4) each resting particle's
/// last stretch of the step on its surface gets the normal force and exact sliding friction (<see cref="CoulombSlide"/>);
/// (5) a few Gauss-Seidel passes push apart what still overlaps (stacks, piles) and take out the approaching velocity.
/// </para>
/// <para>
/// Inside the position-based integrator's substeps the same obstacles and pairs are inequality constraints of zero
/// compliance (<see cref="Project"/>), then restitution and friction act on the velocities (<see cref="SolveVelocities"/>).
/// A step allocates nothing once the buffers have grown to the particle and pair counts.
/// </para>
/// </remarks>
public sealed partial class ContactSet : IStatefulConstraintSet
{
    /// <summary>The most obstacles one set holds (each resting particle keeps the ones it rests on as bits of a mask).</summary>
    public const int MaxObstacles = 64;

    /// <summary>The most impacts <see cref="Impacts"/> keeps per step (<see cref="ImpactCount"/> counts them all).</summary>
    public const int MaxRecordedImpacts = 4096;

    /// <summary>The default <see cref="RestingSpeed"/>, 0.01 m/s.</summary>
    public const double DefaultRestingSpeed = 0.01;

    /// <summary>The default, and the largest allowed, <see cref="MaxCandidatePairs"/>: 2^26 = 67,108,864.</summary>
    public const int DefaultMaxCandidatePairs = SpatialHashGrid.MaxPairs;

    private readonly List<Obstacle> _obstacles = new();
    private readonly ParticlePaths _paths = new();
    private readonly ImpactQueue _queue = new();
    private readonly SpatialHashGrid _sweptGrid = new();
    private readonly SpatialHashGrid _restingGrid = new();
    private readonly ContactImpact[] _impacts = new ContactImpact[MaxRecordedImpacts];
    private ContactImpact[] _savedImpacts = Array.Empty<ContactImpact>(); // the log as it was before a step (BeginStep)
    private int _savedImpactCount;
    private int _savedPairCount;
    private double _restingSpeed = DefaultRestingSpeed;
    private double _particleRestitution;
    private double _particleFriction;
    private int _projectionIterations = 16;
    private int _maxCandidatePairs = DefaultMaxCandidatePairs;
    private int _impactCount;
    private int _capacity = -1;

    // Per particle: the epoch of its path (bumped by every impulse), the obstacles it rests on (a bit mask), the first
    // of them with the time it came to rest, its tangential velocity and its place relative to the obstacle then; the
    // swept box for the broad phase.
    private int[] _epoch = Array.Empty<int>();
    private ulong[] _restingOn = Array.Empty<ulong>();
    private int[] _restObstacle = Array.Empty<int>();
    private double[] _restTime = Array.Empty<double>();
    private Vector3d[] _restTangent = Array.Empty<Vector3d>();
    private Vector3d[] _restPoint = Array.Empty<Vector3d>();
    private double[] _boxMin = Array.Empty<double>();
    private double[] _boxMax = Array.Empty<double>();
    private double[] _sweep = Array.Empty<double>();
    private bool[] _fast = Array.Empty<bool>(); // under substeps: moved its radius or more in the substep

    // The candidate pairs of this step (from the swept grid), whether each came to rest, and each particle's pairs (CSR).
    private int[] _pairFirst = Array.Empty<int>();
    private int[] _pairSecond = Array.Empty<int>();
    private bool[] _pairResting = Array.Empty<bool>();
    private int[] _pairsOfStart = Array.Empty<int>();
    private int[] _pairsOf = Array.Empty<int>();
    private int _pairCount;

    // The separation stage's lists: particles near an obstacle, and the shock pass's ranks and orders.
    private int[] _nearParticle = Array.Empty<int>();
    private int[] _nearObstacle = Array.Empty<int>();
    private int[] _rank = Array.Empty<int>();
    private int[] _frontier = Array.Empty<int>();
    private int[] _rankedStart = Array.Empty<int>();
    private int[] _rankedPairs = Array.Empty<int>();
    private int[] _pairsNear = Array.Empty<int>();

    /// <summary>The obstacles, in the order they were added (an obstacle's index is its place here).</summary>
    public IReadOnlyList<Obstacle> Obstacles => _obstacles;

    /// <summary>True to make particles collide with each other (off by default: obstacles only).</summary>
    public bool ParticleCollisions { get; set; }

    /// <summary>Which particle pairs may collide (null: all of them), for instance <see cref="ExcludedPairs"/>.</summary>
    public IContactPairFilter? PairFilter { get; set; }

    /// <summary>The restitution e of particle-particle impacts, 0 (the default) to 1.</summary>
    public double ParticleRestitution
    {
        get => _particleRestitution;
        set
        {
            CheckRestitution(value, nameof(ParticleRestitution));
            _particleRestitution = value;
        }
    }

    /// <summary>The Coulomb friction mu between particles (a finite number &gt;= 0, default 0).</summary>
    public double ParticleFriction
    {
        get => _particleFriction;
        set
        {
            Guard.NonNegativeFinite(value, nameof(ParticleFriction));
            _particleFriction = value;
        }
    }

    /// <summary>
    /// The rebound speed e u below which an impact does not bounce but comes to rest, in m/s (default 0.01; the
    /// contract allows up to 0.05): it ends the endless train of ever smaller bounces, and a resting particle does not
    /// jitter.
    /// </summary>
    public double RestingSpeed
    {
        get => _restingSpeed;
        set
        {
            Guard.NonNegativeFinite(value, nameof(RestingSpeed));
            _restingSpeed = value;
        }
    }

    /// <summary>
    /// The most Gauss-Seidel passes of the end-of-step separation (default 16, 1 to 1000), before its shock-propagation
    /// pass; it stops sooner once no pass moves anything by more than 1e-6 m. A pile of 1,000 particles in three layers
    /// stays within the contract's 1 % overlap at 1 ms steps with 8 and at 60 Hz with 16 (0.8 %; 3.2 % with 8).
    /// </summary>
    public int ProjectionIterations
    {
        get => _projectionIterations;
        set
        {
            if (value < 1 || value > 1000)
            {
                throw new ArgumentOutOfRangeException(
                    nameof(ProjectionIterations), value, $"ProjectionIterations must be 1 to 1000; got {value}.");
            }

            _projectionIterations = value;
        }
    }

    /// <summary>
    /// The most candidate pairs (particles within reach of each other) a step may have, 1 to
    /// <see cref="DefaultMaxCandidatePairs"/> (the default). The stage's memory grows with the pairs a step finds, about
    /// 40 bytes a pair (80 while its lists double): 2.7 GB at the default, which 11,600 particles heaped at one point
    /// reach. A step whose broad phase finds more throws <see cref="InvalidOperationException"/>: the search stops at the
    /// limit, so nothing past it is allocated, and the world is left as it was. Lower it to fit a host's memory budget.
    /// </summary>
    public int MaxCandidatePairs
    {
        get => _maxCandidatePairs;
        set
        {
            if (value < 1 || value > DefaultMaxCandidatePairs)
            {
                throw new ArgumentOutOfRangeException(
                    nameof(MaxCandidatePairs), value, $"MaxCandidatePairs must be 1 to {DefaultMaxCandidatePairs}; got {value}.");
            }

            _maxCandidatePairs = value;
        }
    }

    /// <summary>The number of impacts the last step (or substep) resolved.</summary>
    public int ImpactCount => _impactCount;

    /// <summary>
    /// The impacts of the last step, in time order (the first <see cref="MaxRecordedImpacts"/>); valid until the next
    /// step. Under the position-based integrator, the contacts of its last substep, timed at that substep's end.
    /// </summary>
    public ReadOnlySpan<ContactImpact> Impacts => _impacts.AsSpan(0, Math.Min(_impactCount, MaxRecordedImpacts));

    /// <summary>The number of particle pairs the broad phase gave the last step.</summary>
    public int CandidatePairCount => _pairCount;

    /// <inheritdoc />
    /// <remarks>Keeps the impact log aside (a copy of the impacts it holds, allocated once).</remarks>
    public void BeginStep()
    {
        if (_savedImpacts.Length == 0)
        {
            _savedImpacts = new ContactImpact[MaxRecordedImpacts];
        }

        _savedImpactCount = _impactCount;
        _savedPairCount = _pairCount;
        Impacts.CopyTo(_savedImpacts);
    }

    /// <inheritdoc />
    public void CommitStep()
    {
    }

    /// <inheritdoc />
    /// <remarks>The impact log, its count and the candidate pairs' count are those of the last committed step again.</remarks>
    public void DiscardStep()
    {
        _impactCount = _savedImpactCount;
        _pairCount = _savedPairCount;
        _savedImpacts.AsSpan(0, Math.Min(_impactCount, MaxRecordedImpacts)).CopyTo(_impacts);
    }

    /// <summary>Adds an obstacle; it acts from the next step on.</summary>
    /// <exception cref="ArgumentException">It is already in the set, or the set holds <see cref="MaxObstacles"/>.</exception>
    public void Add(Obstacle obstacle)
    {
        Guard.NotNull(obstacle, nameof(obstacle));
        if (_obstacles.Contains(obstacle))
        {
            throw new ArgumentException("This obstacle is already in the contact set.", nameof(obstacle));
        }

        if (_obstacles.Count == MaxObstacles)
        {
            throw new ArgumentException(
                $"A contact set holds at most {MaxObstacles} obstacles; add another set for more.", nameof(obstacle));
        }

        _obstacles.Add(obstacle);
    }

    /// <summary>Removes an obstacle; returns false when it was not in the set. The indices of those after it shift down.</summary>
    public bool Remove(Obstacle obstacle) => _obstacles.Remove(obstacle);

    /// <inheritdoc />
    /// <remarks>The stages listed on the class; the end state is corrected in place.</remarks>
    /// <exception cref="InvalidOperationException">More than <see cref="MaxCandidatePairs"/> candidate pairs.</exception>
    public void Resolve(in ConstraintContext context)
    {
        var n = context.Count;
        EnsureCapacity(n);
        _impactCount = 0;
        _pairCount = 0;
        var duration = context.Dt;
        var x0 = context.StartPositions.ForReading();
        var v0 = context.StartVelocities.ForReading();
        var x1 = context.Positions;
        var v1 = context.Velocities;
        var inverseMasses = context.InverseMasses.ForReading();
        var radii = context.Radii.ForReading();
        for (var i = 0; i < n; i++)
        {
            _paths.SetHermite(i, Read(x0, i), Read(v0, i), Read(x1, i), Read(v1, i), duration);
            _epoch[i] = 0;
            _restingOn[i] = 0;
            _restObstacle[i] = -1;
        }

        if (ParticleCollisions)
        {
            FindSweptPairs(n, duration, x0, x1, inverseMasses, radii);
        }

        // Built every step, empty when collisions are off: the impact stage reads each particle's pairs through these
        // lists, and lists left from an earlier step would collide pairs this step does not have.
        IndexPairsByParticle(n);
        ResolveImpacts(in context);
        ApplyRestingFriction(in context);
        Separate(in context, _projectionIterations);
    }

    private void EnsureCapacity(int n)
    {
        if (_capacity >= n)
        {
            return;
        }

        _paths.EnsureCapacity(n);
        _epoch = new int[n];
        _restingOn = new ulong[n];
        _restObstacle = new int[n];
        _restTime = new double[n];
        _restTangent = new Vector3d[n];
        _restPoint = new Vector3d[n];
        _boxMin = new double[3 * n];
        _boxMax = new double[3 * n];
        _sweep = new double[n];
        _fast = new bool[n];
        _pairsOfStart = new int[n + 1];
        _capacity = n;
    }

    /// <summary>The candidate pairs of the step: swept boxes of start and end, grown by the radius and the path's bulge.</summary>
    private void FindSweptPairs(
        int n, double duration, Span<double> x0, Span<double> x1, Span<double> inverseMasses, Span<double> radii)
    {
        for (var i = 0; i < n; i++)
        {
            // A cubic departs from its chord by at most A T^2 / 8 (A: the bound on its second derivative); the quarter
            // radius more keeps the pairs that nearly touch at the end for the separation stage.
            var bulge = 0.125 * _paths.AccelerationBound(i, 0.0, duration) * duration * duration;
            var grow = (1.25 * Radius(radii, i)) + bulge;
            _sweep[i] = Distance(x0, i, x1, i) + bulge;
            for (var c = 0; c < 3; c++)
            {
                var a = x0[(3 * i) + c];
                var b = x1[(3 * i) + c];
                _boxMin[(3 * i) + c] = Math.Min(a, b) - grow;
                _boxMax[(3 * i) + c] = Math.Max(a, b) + grow;
            }
        }

        if (!_sweptGrid.TryFindPairs(_boxMin, _boxMax, n, PairFilter, _maxCandidatePairs))
        {
            RefuseCandidatePairs(n);
        }

        var first = _sweptGrid.First.ForReading();
        var second = _sweptGrid.Second.ForReading();
        var found = _sweptGrid.PairCount;
        if (_pairFirst.Length < found)
        {
            var capacity = Math.Max(found, (int)Math.Min(2L * _pairFirst.Length, DefaultMaxCandidatePairs));
            _pairFirst = new int[capacity];
            _pairSecond = new int[capacity];
            _pairResting = new bool[capacity];
            _pairsOf = new int[2 * capacity];
        }

        var count = 0;
        for (var p = 0; p < found; p++)
        {
            var i = first[p];
            var j = second[p];
            if ((inverseMasses[i] == 0.0 && inverseMasses[j] == 0.0) || !MayMeet(i, j, x0, radii))
            {
                continue; // two pinned particles cannot move; two swept spheres too far apart cannot meet
            }

            _pairFirst[count] = i;
            _pairSecond[count] = j;
            _pairResting[count] = false;
            count++;
        }

        _pairCount = count;
    }

    /// <summary>Each particle's pairs among the step's candidate pairs (none when collisions are off), in pair order (a counting sort of both ends).</summary>
    private void IndexPairsByParticle(int n)
    {
        var count = _pairCount;
        Array.Clear(_pairsOfStart, 0, n + 1);
        for (var p = 0; p < count; p++)
        {
            _pairsOfStart[_pairFirst[p] + 1]++;
            _pairsOfStart[_pairSecond[p] + 1]++;
        }

        for (var i = 0; i < n; i++)
        {
            _pairsOfStart[i + 1] += _pairsOfStart[i];
        }

        for (var p = 0; p < count; p++)
        {
            _pairsOf[_pairsOfStart[_pairFirst[p]]++] = p;
            _pairsOf[_pairsOfStart[_pairSecond[p]]++] = p;
        }

        for (var i = n; i > 0; i--)
        {
            _pairsOfStart[i] = _pairsOfStart[i - 1];
        }

        _pairsOfStart[0] = 0;
    }

    /// <summary>
    /// The narrow test after the boxes, whose corners let through neighbours up to sqrt(3) times too far: a centre
    /// stays within its sweep (chord plus bulge) of where it started, so two particles can come within 1.25 (r_i + r_j)
    /// of each other only if their start distance is at most that plus both sweeps.
    /// </summary>
    private bool MayMeet(int i, int j, Span<double> x0, Span<double> radii) =>
        Distance(x0, i, x0, j) <= (1.25 * (Radius(radii, i) + Radius(radii, j))) + _sweep[i] + _sweep[j];

    private void RefuseCandidatePairs(int n)
    {
        _pairCount = 0;
        throw new InvalidOperationException(
            $"The contact set found more than MaxCandidatePairs = {_maxCandidatePairs} candidate pairs among {n} particles "
            + "(particles heaped within reach of each other): the search stopped there and the step is refused, with "
            + $"nothing changed. Spread the particles out, or raise MaxCandidatePairs (at most {DefaultMaxCandidatePairs}, about 40 bytes a pair).");
    }

    private static double Distance(Span<double> a, int i, Span<double> b, int j)
    {
        var dx = a[3 * i] - b[3 * j];
        var dy = a[(3 * i) + 1] - b[(3 * j) + 1];
        var dz = a[(3 * i) + 2] - b[(3 * j) + 2];
        return Math.Sqrt((dx * dx) + (dy * dy) + (dz * dz));
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static double Radius(Span<double> radii, int i) => radii.Length == 0 ? 0.0 : radii[i];

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector3d Read(Span<double> values, int i) =>
        new(values[3 * i], values[(3 * i) + 1], values[(3 * i) + 2]);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Write(Span<double> values, int i, Vector3d value)
    {
        values[3 * i] = value.X;
        values[(3 * i) + 1] = value.Y;
        values[(3 * i) + 2] = value.Z;
    }

    private static void CheckRestitution(double value, string name)
    {
        if (!(value >= 0.0 && value <= 1.0))
        {
            throw new ArgumentOutOfRangeException(name, value, $"{name} must be from 0 to 1; got {Guard.Format(value)}.");
        }
    }

    private void Record(double time, int particle, int other, bool withObstacle, double speed, bool resting)
    {
        if (_impactCount < MaxRecordedImpacts)
        {
            _impacts[_impactCount] = new ContactImpact(time, particle, other, withObstacle, speed, resting);
        }

        _impactCount++;
    }
}
