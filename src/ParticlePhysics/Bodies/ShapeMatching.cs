using System;
using System.Runtime.CompilerServices;
using ParticlePhysics.Constraints;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Bodies;

/// <summary>
/// Rigid and soft bodies made of particles and held in shape by shape matching (Müller, Heidelberger, Teschner and
/// Gross, "Meshless Deformations Based on Shape Matching", 2005): each body keeps its particles' rest offsets q_i, and
/// each projection moves its particles towards the goals g_i = c + R q_i, with c the centre of mass and R the
/// rotation of the polar decomposition of A_pq = sum_i m_i (x_i - c) q_i^T (<see cref="RotationExtraction"/>).
/// </summary>
/// <remarks>
/// <para>
/// A rigid body (<see cref="AddRigid"/>) is projected onto its goals exactly, and is predicted along its rotation
/// rather than along straight lines: plain PBD moves each particle along its velocity and projects back, which shrinks
/// the body's spin by about (omega h)^2 / 2 per substep (4 % in 12 s at 3 rad/s and h = 1/1200 s), so a spinning box
/// slowly stops. Here a substep from (x0, v0) takes the angular momentum L = sum m (x0 - c0) x (x - x0) / h of the
/// prediction x (forces' torques included), turns the body by exp(omega h) with omega = I^-1 L at the orientation
/// half-way (second order), places the goals there, and after the substep sets the velocities to the rigid field
/// V + omega x (x - c) with omega = I^-1 L of the same L, plus what other sets (contacts) changed it by since. Free
/// flight then keeps |L| to rounding, and the shape to rounding of its size.
/// </para>
/// <para>
/// A soft body (<see cref="AddSoft"/>) moves its particles a fraction s (its stiffness, 0 &lt; s &lt;= 1) of the way to
/// their goals at every projection (once per xpbd substep), as in Müller et al.; s = 1 holds the shape as a rigid
/// body does, but with plain PBD's prediction. A plastic one (<see cref="SetPlasticity"/>) takes what is pulled past
/// the yield into its rest shape.
/// </para>
/// <para>
/// Under a force-based integrator the end of the step is projected the same way, the step taken as one substep: a rigid
/// body turns by the angular momentum of the end velocities (about the start's offsets, which the straight-line step
/// has not stretched) and takes the rigid velocity field; a soft body's correction dx also changes its velocity by dx / dt. Two particles of one body do not collide: give the
/// contact set <see cref="PairFilter"/>. The set keeps each body's orientation, so the world brackets it
/// (<see cref="IStatefulConstraintSet"/>): a failed step leaves the orientations (and plastic bodies' rest shapes) as they were. Nothing is allocated per
/// step. A pinned particle of a body stays where its pin holds it.
/// </para>
/// </remarks>
public sealed partial class ShapeMatching : IStatefulConstraintSet, IParticleLinks
{
    private readonly ParticleWorld _world;
    private int _revision; // bumped by a new body or new plasticity: sleeping islands wake (IParticleLinks)
    private int _bodies;
    private int _entries;
    private int[] _start = { 0 };
    private double[] _stiffness = Array.Empty<double>();
    private bool[] _rigid = Array.Empty<bool>();
    private Quaternion4d[] _orientation = Array.Empty<Quaternion4d>();
    private Quaternion4d[] _saved = Array.Empty<Quaternion4d>();
    private Quaternion4d[] _predicted = Array.Empty<Quaternion4d>();
    private Vector3d[] _momentum = Array.Empty<Vector3d>();
    private bool[] _slept = Array.Empty<bool>(); // asleep at this substep's projection: no momentum of its own to take velocities from
    private int[] _particles = Array.Empty<int>();
    private Vector3d[] _rest = Array.Empty<Vector3d>();
    private Vector3d[] _goals = Array.Empty<Vector3d>();
    private int[] _bodyOf = Array.Empty<int>();

    /// <summary>An empty set for the bodies of <paramref name="world"/>; add it with <see cref="ParticleWorld.AddConstraints"/>.</summary>
    public ShapeMatching(ParticleWorld world)
    {
        Guard.NotNull(world, nameof(world));
        _world = world;
        PairFilter = new BodyPairFilter(this);
    }

    /// <summary>The number of bodies.</summary>
    public int Count => _bodies;

    /// <summary>The filter that keeps two particles of one body from colliding: set it as the contact set's pair filter.</summary>
    public BodyPairFilter PairFilter { get; }

    /// <summary>
    /// Adds a rigid body of the particles listed, in the shape they have now; its frame is the world's turned by
    /// <paramref name="rotation"/> about their centre of mass (the identity when omitted), so that
    /// <see cref="GetPose"/> reports the rotation of a mesh modelled in that frame. Returns the body's index.
    /// </summary>
    /// <exception cref="ArgumentException">
    /// No particle is listed, one is listed twice or belongs to another body, or they all lie on one line (the spin
    /// about that line would be undefined).
    /// </exception>
    public int AddRigid(ReadOnlySpan<int> particles, Rotation3d rotation = default) => Add(particles, 1.0, rigid: true, rotation);

    /// <summary>
    /// Adds a soft body of the particles listed, in the shape they have now, that moves them the fraction
    /// <paramref name="stiffness"/> of the way to their goals at each projection (0 &lt; s &lt;= 1). Returns its index.
    /// </summary>
    /// <exception cref="ArgumentException">No particle is listed, one is listed twice or belongs to another body, or the stiffness is not in (0, 1].</exception>
    public int AddSoft(ReadOnlySpan<int> particles, double stiffness, Rotation3d rotation = default)
    {
        if (!(stiffness > 0.0 && stiffness <= 1.0))
        {
            throw new ArgumentOutOfRangeException(nameof(stiffness), stiffness, $"stiffness must be in (0, 1]; got {Guard.Format(stiffness)}.");
        }

        return Add(particles, stiffness, rigid: false, rotation);
    }

    /// <summary>Whether body <paramref name="body"/> is rigid.</summary>
    public bool IsRigid(int body)
    {
        CheckBody(body);
        return _rigid[body];
    }

    /// <summary>The stiffness of body <paramref name="body"/> (1 for a rigid one).</summary>
    public double GetStiffness(int body)
    {
        CheckBody(body);
        return _stiffness[body];
    }

    /// <summary>The world's indices of the particles of body <paramref name="body"/>, in the order they were given.</summary>
    public ReadOnlySpan<int> ParticlesOf(int body)
    {
        CheckBody(body);
        return _particles.AsSpan(_start[body], _start[body + 1] - _start[body]);
    }

    /// <summary>The rest offsets of body <paramref name="body"/>'s particles in its own frame, m, in the order of <see cref="ParticlesOf"/>.</summary>
    public ReadOnlySpan<Vector3d> RestShapeOf(int body)
    {
        CheckBody(body);
        return _rest.AsSpan(_start[body], _start[body + 1] - _start[body]);
    }

    /// <summary>The body particle <paramref name="particle"/> belongs to, or -1.</summary>
    public int BodyOfParticle(int particle) => (uint)particle < (uint)_bodyOf.Length ? _bodyOf[particle] : -1;

    /// <summary>The pose of body <paramref name="body"/> in the world's current state.</summary>
    public BodyPose GetPose(int body)
    {
        CheckBody(body);
        var x = _world.Positions.ForReading();
        var v = _world.Velocities.ForReading();
        var m = _world.Masses.ForReading();
        var (first, end) = (_start[body], _start[body + 1]);
        var (mass, c, restCentre) = Centres(first, end, x, m);
        var velocity = Vector3d.Zero;
        var momentum = Vector3d.Zero;
        for (var k = first; k < end; k++)
        {
            var i = _particles[k];
            var vi = At(v, i);
            velocity += m[i] * vi;
            momentum += m[i] * Vector3d.Cross(At(x, i) - c, vi);
        }

        velocity /= mass;
        var q = _orientation[body];
        var omega = InertiaOf(body, m, restCentre).AngularVelocity(q, momentum);
        return new BodyPose(c - q.Rotate(restCentre), q.ToRotation(), velocity, omega);
    }

    /// <summary>
    /// Sets the velocities of body <paramref name="body"/>'s particles to those of a rigid motion: the centre of mass at
    /// <paramref name="linearVelocity"/> (m/s), turning at <paramref name="angularVelocity"/> (rad/s, world axes) about it.
    /// Pinned particles keep theirs. Only between steps.
    /// </summary>
    public void SetMotion(int body, Vector3d linearVelocity, Vector3d angularVelocity)
    {
        _world.ThrowIfStepping();
        CheckBody(body);
        Guard.Finite(linearVelocity, nameof(linearVelocity));
        Guard.Finite(angularVelocity, nameof(angularVelocity));
        var x = _world.Positions.ForReading();
        var (_, c, _) = Centres(_start[body], _start[body + 1], x, _world.Masses.ForReading());
        for (var k = _start[body]; k < _start[body + 1]; k++)
        {
            var i = _particles[k];
            if (!_world.IsPinned(i))
            {
                _world.SetVelocity(i, linearVelocity + Vector3d.Cross(angularVelocity, At(x, i) - c));
            }
        }
    }

    /// <inheritdoc />
    public void BeginStep()
    {
        Array.Copy(_orientation, _saved, _bodies);
        SaveRestShapes();
    }

    /// <inheritdoc />
    public void CommitStep()
    {
    }

    /// <inheritdoc />
    public void DiscardStep()
    {
        Array.Copy(_saved, _orientation, _bodies);
        RestoreRestShapes();
    }

    /// <inheritdoc />
    /// <remarks>
    /// The step as one substep: rigid bodies turn by the angular momentum of the end velocities and take the rigid
    /// velocity field; soft bodies move towards their goals and v += dx / dt.
    /// </remarks>
    public void Resolve(in ConstraintContext context)
    {
        for (var b = 0; b < _bodies; b++)
        {
            if (_rigid[b])
            {
                ProjectRigid(b, context, fromVelocities: true);
            }
            else
            {
                ProjectSoft(b, context, kickVelocities: true);
            }
        }
    }

    /// <inheritdoc />
    public void Project(in ConstraintContext context)
    {
        if (_slept.Length < _bodies)
        {
            _slept = new bool[_stiffness.Length];
        }

        for (var b = 0; b < _bodies; b++)
        {
            // A body woken later in this substep (by the contact stage) takes its velocities from its moves alone.
            _slept[b] = Sleeps(b, in context);
            if (_slept[b])
            {
                continue;
            }

            if (_rigid[b])
            {
                ProjectRigid(b, context);
            }
            else
            {
                ProjectSoft(b, context, kickVelocities: false);
            }
        }
    }

    /// <inheritdoc />
    /// <remarks>Rigid bodies take the rigid velocity field of their angular momentum; soft bodies are left alone.</remarks>
    public void SolveVelocities(in ConstraintContext context)
    {
        for (var b = 0; b < _bodies; b++)
        {
            if (_rigid[b] && !(b < _slept.Length && _slept[b]))
            {
                SolveRigidVelocities(b, context);
            }
        }
    }

    /// <inheritdoc />
    public int Revision => _revision;

    /// <inheritdoc />
    /// <remarks>Each body's particles are one island: a body sleeps and wakes whole.</remarks>
    public void AddLinks(ParticleIslands islands)
    {
        Guard.NotNull(islands, nameof(islands));
        for (var b = 0; b < _bodies; b++)
        {
            for (var k = _start[b] + 1; k < _start[b + 1]; k++)
            {
                islands.Link(_particles[_start[b]], _particles[k]);
            }
        }
    }

    // A body sleeps whole (its particles are one island), so its first particle tells; a sleeping body costs nothing.
    private bool Sleeps(int body, in ConstraintContext context) =>
        context.Sleeping is { } sleeping && sleeping.IsAsleep(_particles[_start[body]]);

    private int Add(ReadOnlySpan<int> given, double stiffness, bool rigid, Rotation3d rotation)
    {
        var particles = given.ForReading();
        _world.ThrowIfStepping();
        if (particles.Length == 0)
        {
            throw new ArgumentException("A body needs at least one particle; none was listed.", nameof(particles));
        }

        var count = _world.Count;
        if (_bodyOf.Length < count)
        {
            var grown = new int[count];
            grown.AsSpan().Fill(-1);
            _bodyOf.AsSpan().CopyTo(grown);
            _bodyOf = grown;
        }

        for (var k = 0; k < particles.Length; k++)
        {
            var i = particles[k];
            Guard.ParticleIndex(i, count, nameof(particles));
            if (_bodyOf[i] >= 0)
            {
                throw new ArgumentException($"Particle {i} already belongs to body {_bodyOf[i]}: a particle belongs to one body at most.", nameof(particles));
            }
        }

        Guard.NoDuplicateParticles(particles, nameof(particles));

        // The rest offsets in the body's frame, from the centre of mass now.
        var x = _world.Positions.ForReading();
        var m = _world.Masses.ForReading();
        var mass = 0.0;
        var centre = Vector3d.Zero;
        foreach (var i in particles)
        {
            mass += m[i];
            centre += m[i] * At(x, i);
        }

        centre /= mass;
        var q = Quaternion4d.FromRotation(rotation);
        var rest = new Vector3d[particles.Length];
        for (var k = 0; k < rest.Length; k++)
        {
            rest[k] = q.RotateInverse(At(x, particles[k]) - centre);
        }

        if (rigid && particles.Length > 1 && !InertiaIsRegular(rest, particles, m))
        {
            throw new ArgumentException(
                $"The {particles.Length} particles of the rigid body lie on one line: its spin about that line would be undefined; add a particle off the line.", nameof(particles));
        }

        // Commit: nothing above changed the set.
        var b = _bodies;
        var first = _entries;
        EnsureCapacity(b + 1, first + particles.Length);
        _start[b + 1] = first + particles.Length;
        _stiffness[b] = stiffness;
        _rigid[b] = rigid;
        _orientation[b] = q;
        _saved[b] = q;
        _predicted[b] = q;
        for (var k = 0; k < particles.Length; k++)
        {
            _particles[first + k] = particles[k];
            _rest[first + k] = rest[k];
            _bodyOf[particles[k]] = b;
        }

        _entries += particles.Length;
        _bodies++;
        _revision++;
        return b;
    }

    private void EnsureCapacity(int bodies, int entries)
    {
        if (bodies > _stiffness.Length)
        {
            var capacity = Math.Max(8, 2 * _stiffness.Length);
            Array.Resize(ref _start, capacity + 1);
            Array.Resize(ref _stiffness, capacity);
            Array.Resize(ref _rigid, capacity);
            Array.Resize(ref _orientation, capacity);
            Array.Resize(ref _saved, capacity);
            Array.Resize(ref _predicted, capacity);
            Array.Resize(ref _momentum, capacity);
        }

        if (entries > _particles.Length)
        {
            var capacity = Math.Max(entries, 2 * _particles.Length);
            Array.Resize(ref _particles, capacity);
            Array.Resize(ref _rest, capacity);
            if (_savedRest.Length > 0)
            {
                Array.Resize(ref _savedRest, capacity); // a plastic body's rest shapes are bracketed
            }

            Array.Resize(ref _goals, capacity);
        }
    }

    private void CheckBody(int body)
    {
        if ((uint)body >= (uint)_bodies)
        {
            throw new ArgumentOutOfRangeException(nameof(body), body, _bodies == 0 ? "The set has no body yet." : $"body must be 0 to {_bodies - 1}; got {body}.");
        }
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector3d At(Span<double> values, int i) => new(values[3 * i], values[(3 * i) + 1], values[(3 * i) + 2]);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Put(Span<double> values, int i, Vector3d value)
    {
        values[3 * i] = value.X;
        values[(3 * i) + 1] = value.Y;
        values[(3 * i) + 2] = value.Z;
    }
}
