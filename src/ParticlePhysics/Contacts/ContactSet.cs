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
public sealed partial class ContactSet : IStatefulConstraintSet, IParticleLinks
{
    /// <summary>The most impacts <see cref="Impacts"/> keeps per step (<see cref="ImpactCount"/> counts them all).</summary>
    public const int MaxRecordedImpacts = 4096;

    /// <summary>The default <see cref="RestingSpeed"/>, 0.01 m/s.</summary>
    public const double DefaultRestingSpeed = 0.01;

    /// <summary>The default, and the largest allowed, <see cref="MaxCandidatePairs"/>: 2^26 = 67,108,864.</summary>
    public const int DefaultMaxCandidatePairs = SpatialHashGrid.MaxPairs;

    // Settings.
    private readonly List<Obstacle> _obstacles = new();
    private double _restingSpeed = DefaultRestingSpeed;
    private double _particleRestitution;
    private double _particleFriction;
    private int _projectionIterations = 16;
    private int _maxCandidatePairs = DefaultMaxCandidatePairs;

    // The state of a step, a type per job, in the order of the stages (docs/architecture.md, "Contacts"): the paths
    // (1), the broad phase's boxes, grids and pairs (2), the queue of impacts (3), who rests on what (4), the
    // separation's lists (5), the substeps' contacts, and what the last step shows.
    private readonly ParticlePaths _paths = new();
    private readonly ParticleBoxes _boxes = new();
    private readonly SpatialHashGrid _sweptGrid = new();
    private readonly SpatialHashGrid _restingGrid = new();
    private readonly CandidatePairs _pairs = new();
    private readonly ImpactQueue _queue = new();
    private readonly RestingContacts _resting = new();
    private readonly ObstacleContactList _near = new();
    private readonly ShockOrder _shock = new();
    private readonly SubstepContacts _substep = new();
    private readonly ContactLog _log = new(MaxRecordedImpacts);
    private readonly ObstacleBroadPhase _colliders = new();
    private readonly ColliderReactions _reactions = new();
    private bool _bracketed;
    private readonly LayeredPairFilter _layered = new();
    private int[] _candidates = Array.Empty<int>();
    private CollisionFilter[] _particleFilters = Array.Empty<CollisionFilter>();
    private bool _anyParticleFilter;
    private int _capacity = -1;

    // Per particle, a fact about the last obstacle it was found far outside of (Obstacle.IsFarOutside): phi at a point
    // of that obstacle's own frame is at least the gap. A fact about the shape's geometry, true whichever particle or
    // step wrote it, so it needs no invalidation; the slot only keeps one near where it is asked.
    private bool _particleCollisions;
    private int _revision; // bumped by a change that may move a particle at rest: sleeping islands wake (IParticleLinks)

    private Obstacle?[] _farObstacles = Array.Empty<Obstacle?>();
    private Vector3d[] _farPoints = Array.Empty<Vector3d>();
    private double[] _farGaps = Array.Empty<double>();

    /// <summary>The obstacles, in the order they were added (an obstacle's index is its place here).</summary>
    public IReadOnlyList<Obstacle> Obstacles => _obstacles;

    /// <summary>True to make particles collide with each other (off by default: obstacles only).</summary>
    public bool ParticleCollisions
    {
        get => _particleCollisions;
        set
        {
            _revision += _particleCollisions != value ? 1 : 0;
            _particleCollisions = value;
        }
    }

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
            _revision++;
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
    public int ImpactCount => _log.Count;

    /// <summary>
    /// The impacts of the last step, in time order (the first <see cref="MaxRecordedImpacts"/>); valid until the next
    /// step. Under the position-based integrator, the contacts of its last substep, timed at that substep's end.
    /// </summary>
    public ReadOnlySpan<ContactImpact> Impacts => _log.Impacts;

    /// <summary>The number of particle pairs the broad phase gave the last step.</summary>
    public int CandidatePairCount => _log.CandidatePairs;

    /// <inheritdoc />
    /// <remarks>Keeps the impact log and the reactions aside (copies allocated once), and starts the reactions from zero.</remarks>
    public void BeginStep()
    {
        _log.Save();
        _reactions.Save();
        SaveSpins();
        _reactions.Clear(_obstacles.Count);
        _bracketed = true;
    }

    /// <inheritdoc />
    public void CommitStep() => _bracketed = false;

    /// <inheritdoc />
    /// <remarks>The impact log, its count, the candidate pairs' count and the reactions are those of the last committed step again.</remarks>
    public void DiscardStep()
    {
        _log.Restore();
        _reactions.Restore();
        RestoreSpins();
        _bracketed = false;
    }

    /// <summary>
    /// What obstacle <paramref name="obstacle"/> received from the particles over the last step (over a
    /// <see cref="Driver.FixedTimestepDriver"/>'s frame, its steps together): the total impulse and the angular impulse
    /// about its <see cref="Obstacle.ReactionPoint"/>, from every impact, resting contact, friction and separation
    /// (under the position-based integrator, m dx / h of each projection and m dv of each velocity pass), so that
    /// a host that moves the obstacle as a body by them conserves the momentum of the two together. Zero for an
    /// obstacle added since. Allocates nothing.
    /// </summary>
    /// <exception cref="ArgumentException">The obstacle is not in the set.</exception>
    public ColliderReaction ReactionOf(Obstacle obstacle)
    {
        Guard.NotNull(obstacle, nameof(obstacle));
        var k = _obstacles.IndexOf(obstacle);
        if (k < 0)
        {
            throw new ArgumentException("This obstacle is not in the contact set.", nameof(obstacle));
        }

        return _reactions.Of(k);
    }

    /// <summary>Adds an obstacle; it acts from the next step on.</summary>
    /// <remarks>Any number: a broad phase over the obstacles' boxes (<see cref="Obstacle.TryGetBounds"/>) tests each particle only against those near it.</remarks>
    /// <exception cref="ArgumentException">It is already in the set.</exception>
    public void Add(Obstacle obstacle)
    {
        Guard.NotNull(obstacle, nameof(obstacle));
        if (_obstacles.Contains(obstacle))
        {
            throw new ArgumentException("This obstacle is already in the contact set.", nameof(obstacle));
        }

        _obstacles.Add(obstacle);
        _reactions.Clear(_obstacles.Count);
        _revision++;
    }

    /// <summary>Removes an obstacle; returns false when it was not in the set. The indices of those after it shift down.</summary>
    /// <remarks>The reactions of the last step start again from zero, since the indices moved.</remarks>
    public bool Remove(Obstacle obstacle)
    {
        var removed = _obstacles.Remove(obstacle);
        _reactions.Clear(_obstacles.Count);
        _revision += removed ? 1 : 0;
        return removed;
    }

    /// <summary>
    /// Puts the particles <paramref name="first"/> to <paramref name="first"/> + <paramref name="count"/> - 1 (a cloth,
    /// a rope, a body) under <paramref name="filter"/>: they meet an obstacle, or another particle, only when the two
    /// filters accept each other (<see cref="CollisionFilter"/>). Particles never set have the default, layer 1 and
    /// every layer; indices past the world's particles apply to the particles added there later.
    /// </summary>
    /// <exception cref="ArgumentOutOfRangeException"><paramref name="first"/> or <paramref name="count"/> is negative, or their sum passes <see cref="ParticleWorld.MaxParticles"/>.</exception>
    public void SetParticleFilter(int first, int count, CollisionFilter filter)
    {
        CheckParticleRange(first, count);

        if (_particleFilters.Length < first + count)
        {
            Array.Resize(ref _particleFilters, Math.Max(first + count, 2 * _particleFilters.Length));
            _layered.Use(_particleFilters);
        }

        _particleFilters.AsSpan(first, count).Fill(filter);
        _anyParticleFilter |= filter != CollisionFilter.Default;
    }

    /// <summary>Refuses a range of particles that starts below 0 or ends past <see cref="ParticleWorld.MaxParticles"/>.</summary>
    private static void CheckParticleRange(int first, int count)
    {
        if (first < 0 || first > ParticleWorld.MaxParticles)
        {
            throw new ArgumentOutOfRangeException(nameof(first), first, $"first must be a particle index from 0 to {ParticleWorld.MaxParticles}; got {first}.");
        }

        if (count < 0 || count > ParticleWorld.MaxParticles - first)
        {
            throw new ArgumentOutOfRangeException(nameof(count), count, $"count must be from 0 to {ParticleWorld.MaxParticles - first} (first + count at most {ParticleWorld.MaxParticles}); got {count}.");
        }
    }

    /// <summary>The filter of particle <paramref name="particle"/> (<see cref="SetParticleFilter"/>; the default if never set).</summary>
    public CollisionFilter GetParticleFilter(int particle)
    {
        if (particle < 0)
        {
            throw new ArgumentOutOfRangeException(nameof(particle), particle, $"particle must be an index >= 0; got {particle}.");
        }

        return ParticleFilter(particle);
    }

    /// <inheritdoc />
    /// <remarks>The stages listed on the class; the end state is corrected in place.</remarks>
    /// <exception cref="InvalidOperationException">More than <see cref="MaxCandidatePairs"/> candidate pairs.</exception>
    public void Resolve(in ConstraintContext context)
    {
        var n = context.Count;
        EnsureCapacity(n);
        _log.Clear();
        _pairs.Clear();
        if (!_bracketed)
        {
            _reactions.Clear(_obstacles.Count); // called outside a world's step: this call's reactions alone
        }

        UpdateObstacleBoxes(context.Time, context.Time + context.Dt);
        SetPaths(in context);
        _resting.Clear(n);
        if (ParticleCollisions)
        {
            FindSweptPairs(in context);
        }

        // Indexed every step, empty when collisions are off: the impact stage reads each particle's pairs through the
        // index, and an index left from an earlier step would collide pairs this step does not have.
        _pairs.IndexByParticle(n);
        ResolveImpacts(in context);
        ApplyRestingFriction(in context);
        Separate(in context, _projectionIterations);
        CountContacts(_log.Count);
    }

    private void EnsureCapacity(int n)
    {
        if (_capacity >= n)
        {
            return;
        }

        _paths.EnsureCapacity(n);
        _boxes.EnsureCapacity(n);
        _pairs.EnsureParticles(n);
        _resting.EnsureCapacity(n);
        _farObstacles = new Obstacle?[n];
        _farPoints = new Vector3d[n];
        _farGaps = new double[n];
        _capacity = n;
    }

    /// <summary>Stage 1: each particle's path within the step, the cubic through its start and end (<see cref="ParticlePaths"/>).</summary>
    private void SetPaths(in ConstraintContext context)
    {
        var x0 = context.StartPositions.ForReading();
        var v0 = context.StartVelocities.ForReading();
        var x1 = context.Positions;
        var v1 = context.Velocities;
        for (var i = 0; i < context.Count; i++)
        {
            _paths.SetHermite(i, Read(x0, i), Read(v0, i), Read(x1, i), Read(v1, i), context.Dt);
        }
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

    /// <summary>
    /// Books on obstacle k the reaction to particle i's velocity change <paramref name="dv"/> at time
    /// <paramref name="time"/>: the impulse -m dv at the contact point, the centre less the radius along the normal.
    /// </summary>
    private void React(in ConstraintContext context, int i, int k, Vector3d dv, Vector3d centre, Vector3d normal, double time)
    {
        if (dv == Vector3d.Zero)
        {
            return;
        }

        var obstacle = _obstacles[k];
        var point = centre - (Radius(context.Radii.ForReading(), i) * normal);
        _reactions.Add(k, -context.Masses.ForReading()[i] * dv, point, obstacle.ReactionPoint + obstacle.OffsetAt(time));
    }

    private static void CheckRestitution(double value, string name)
    {
        if (!(value >= 0.0 && value <= 1.0))
        {
            throw new ArgumentOutOfRangeException(name, value, $"{name} must be from 0 to 1; got {Guard.Format(value)}.");
        }
    }
}
