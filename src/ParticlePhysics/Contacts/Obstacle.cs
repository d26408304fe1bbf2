namespace ParticlePhysics.Contacts;

/// <summary>
/// A shape that particles cannot enter (a collider): a particle of radius r touches it when its centre is at distance
/// r from its surface. Each obstacle has a restitution e and a Coulomb friction coefficient mu, and may move
/// (kinematic): it translates with <see cref="Velocity"/>, and that velocity enters its contacts.
/// </summary>
/// <remarks>
/// <para>
/// Motion: the shape's parameters (a sphere's centre, ...) say where it is at <see cref="ReferenceTime"/>; at time t
/// it is translated by Velocity (t - ReferenceTime). A still obstacle has Velocity 0 and is where its parameters say at
/// every time. A host that drives an obstacle along a path of its own sets, between steps, <see cref="Rebase"/> (or the
/// shape's parameters and <see cref="ReferenceTime"/>) and the velocity for the next step. Nothing in a step changes an
/// obstacle, so a step that fails leaves it as it was too.
/// </para>
/// <para>
/// Shapes are given by their signed distance function phi(p) (negative inside), which for these convex shapes is
/// convex and 1-Lipschitz: that is what the contact search relies on to never step past a first contact.
/// Rotation is not part of the motion: a host that turns an obstacle between steps moves it at once, and particles it
/// then overlaps are pushed out at the next step.
/// </para>
/// </remarks>
public abstract class Obstacle
{
    private double _restitution;
    private double _friction;
    private Vector3d _velocity;
    private double _referenceTime;

    /// <summary>Sets the contact coefficients.</summary>
    /// <param name="restitution">e, from 0 (no bounce) to 1 (elastic).</param>
    /// <param name="friction">mu, a finite number &gt;= 0.</param>
    protected Obstacle(double restitution, double friction)
    {
        Restitution = restitution;
        Friction = friction;
    }

    /// <summary>
    /// The restitution e, 0 to 1: an impact at normal speed u leaves at e u (below
    /// <see cref="ContactSet.RestingSpeed"/> it does not bounce but rests).
    /// </summary>
    public double Restitution
    {
        get => _restitution;
        set
        {
            if (!(value >= 0.0 && value <= 1.0))
            {
                throw new System.ArgumentOutOfRangeException(
                    nameof(Restitution), value, $"Restitution must be from 0 to 1; got {Guard.Format(value)}.");
            }

            _restitution = value;
        }
    }

    /// <summary>The Coulomb friction coefficient mu (a finite number &gt;= 0): the tangential impulse is at most mu times the normal one.</summary>
    public double Friction
    {
        get => _friction;
        set
        {
            Guard.NonNegativeFinite(value, nameof(Friction));
            _friction = value;
        }
    }

    /// <summary>The obstacle's velocity, in m/s (zero by default): it moves with it, and its contacts see it.</summary>
    public Vector3d Velocity
    {
        get => _velocity;
        set
        {
            Guard.Finite(value, nameof(Velocity));
            _velocity = value;
        }
    }

    /// <summary>The time, in seconds, at which the obstacle is where its parameters say (0 by default).</summary>
    public double ReferenceTime
    {
        get => _referenceTime;
        set
        {
            Guard.Finite(value, nameof(ReferenceTime));
            _referenceTime = value;
        }
    }

    /// <summary>What a renderer needs to draw the obstacle where its parameters put it (at <see cref="ReferenceTime"/>).</summary>
    public ObstacleShape Shape => Describe(Vector3d.Zero);

    /// <summary>What a renderer needs to draw the obstacle at <paramref name="time"/> (it moves with <see cref="Velocity"/>).</summary>
    public ObstacleShape ShapeAt(double time) => Describe(OffsetAt(time));

    /// <summary>
    /// Moves the obstacle's parameters to where it is at <paramref name="time"/> and makes that its
    /// <see cref="ReferenceTime"/>, so that a new <see cref="Velocity"/> starts from there without a jump.
    /// </summary>
    public void Rebase(double time)
    {
        Guard.Finite(time, nameof(time));
        var offset = OffsetAt(time);
        Guard.Finite(offset, nameof(time));
        Translate(offset);
        _referenceTime = time;
    }

    /// <summary>Moves the obstacle by <paramref name="offset"/> at once (its parameters; not its velocity).</summary>
    public abstract void Translate(Vector3d offset);

    /// <summary>
    /// The signed distance from <paramref name="point"/> to the surface where the parameters put it (negative inside),
    /// and the outward unit normal there (the gradient of the distance).
    /// </summary>
    public double SignedDistance(Vector3d point, out Vector3d normal)
    {
        var d = Distance(point.X, point.Y, point.Z, out var nx, out var ny, out var nz);
        normal = new Vector3d(nx, ny, nz);
        return d;
    }

    /// <summary>The translation from the parameters' position to the position at <paramref name="time"/>.</summary>
    internal Vector3d OffsetAt(double time) => (time - _referenceTime) * _velocity;

    /// <summary>The description with the shape moved by <paramref name="offset"/>.</summary>
    private protected abstract ObstacleShape Describe(Vector3d offset);

    /// <summary>
    /// The signed distance of (x, y, z) to the surface at the parameters' position, and the outward unit normal: the
    /// hot path of the contact search, without vectors.
    /// </summary>
    internal abstract double Distance(double x, double y, double z, out double nx, out double ny, out double nz);
}
