using System;

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
/// Shapes are given by their signed distance function phi(p) (negative inside) and its gradient, the outward normal
/// (<see cref="Distance"/>). phi must be 1-Lipschitz, |phi(p) - phi(q)| &lt;= |p - q|, which every exact signed
/// distance is: that is what the contact search relies on to never step past a first contact. A convex shape's phi is
/// also convex (<see cref="IsConvex"/>), and the search then steps by the tangent's bound, which lands on a contact in
/// a few steps; a shape that is not convex is stepped by the Lipschitz bound alone, or by a bound of its own (the
/// triangle meshes and height fields take the least of their triangles' convex bounds).
/// Rotation is not part of the motion: a host that turns an obstacle between steps moves it at once, and particles it
/// then overlaps are pushed out at the next step.
/// </para>
/// <para>
/// A shape of your own derives from this class and implements <see cref="Distance"/>, <see cref="Describe"/> and
/// <see cref="Translate"/>; it may say that it is convex (<see cref="IsConvex"/>), give a bounding box
/// (<see cref="TryGetBounds"/>, so that a set of many obstacles tests it only against particles near it), and a cast
/// of its own (<see cref="Cast"/>; by default a search along the ray by the same safe steps). Its members are called
/// from inside the world's step, so they must be deterministic, allocate nothing and leave the obstacle unchanged.
/// </para>
/// </remarks>
public abstract class Obstacle
{
    private double _restitution;
    private double _friction;
    private Vector3d _velocity;
    private double _referenceTime;
    private Vector3d _reactionPoint;

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

    /// <summary>
    /// Which particles it collides with (<see cref="CollisionFilter"/>: its layers against the particles' masks and back;
    /// by default layer 1 and every layer, so every particle).
    /// </summary>
    public CollisionFilter Filter { get; set; }

    /// <summary>
    /// The point about which <see cref="ContactSet.ReactionOf"/> gives the angular impulse the particles exert, in
    /// metres where the parameters put the obstacle (the origin by default): a host body's centre of mass. It moves
    /// with the obstacle, as its parameters do.
    /// </summary>
    public Vector3d ReactionPoint
    {
        get => _reactionPoint;
        set
        {
            Guard.Finite(value, nameof(ReactionPoint));
            _reactionPoint = value;
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
        _reactionPoint += offset;
        _referenceTime = time;
    }

    /// <summary>Moves the obstacle by <paramref name="offset"/> at once (its parameters; not its velocity).</summary>
    /// <param name="offset">The translation, in metres.</param>
    public abstract void Translate(Vector3d offset);

    /// <summary>
    /// True when the shape is convex, so that its signed distance is a convex function (planes, spheres, capsules and
    /// boxes): the contact search then steps to the root of phi + phi' u - A u^2 / 2 (the tangent bound, A the path's
    /// bend), which converges in a few steps. False (the default) for any other shape: the search steps by the
    /// Lipschitz bound phi - |w| u - A u^2 / 2 (w the velocity relative to the obstacle), valid for any 1-Lipschitz phi
    /// but slow on paths that graze the surface (it gives up after 64 steps, and the end-of-step separation then keeps
    /// the particle out). Claiming convexity for a shape that is not lets a particle pass a concave part of it.
    /// </summary>
    public virtual bool IsConvex => false;

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

    /// <summary>
    /// The signed distance phi of (x, y, z) to the surface where the parameters put the shape (negative inside, 0 on
    /// it), and the outward unit normal there, the gradient of phi (any unit vector where phi has no gradient, such as
    /// a sphere's centre): the hot path of the contact search, without vectors.
    /// </summary>
    /// <remarks>
    /// phi must be 1-Lipschitz (an exact signed distance is), finite for finite arguments, and must not allocate; the
    /// normal must be of unit length. A shape with no inside (an open sheet) returns the unsigned distance, and the
    /// normal pointing from the surface to the point.
    /// </remarks>
    /// <param name="x">The point's x, in metres.</param>
    /// <param name="y">The point's y.</param>
    /// <param name="z">The point's z.</param>
    /// <param name="nx">Receives the normal's x.</param>
    /// <param name="ny">Receives the normal's y.</param>
    /// <param name="nz">Receives the normal's z.</param>
    /// <returns>phi, in metres.</returns>
    public abstract double Distance(double x, double y, double z, out double nx, out double ny, out double nz);

    /// <summary>
    /// An axis-aligned box around the shape where its parameters put it: every point whose <see cref="Distance"/> is
    /// less than d lies within d of the box, for every d &gt;= 0 (true of any box that holds the whole solid when phi
    /// is its exact signed distance). False for a shape without bounds (a plane; the default), which is then tested
    /// against every particle.
    /// </summary>
    /// <param name="min">Receives the box's lower corner.</param>
    /// <param name="max">Receives its upper corner.</param>
    /// <returns>Whether the shape is bounded.</returns>
    public virtual bool TryGetBounds(out Vector3d min, out Vector3d max)
    {
        min = new Vector3d(double.NegativeInfinity, double.NegativeInfinity, double.NegativeInfinity);
        max = new Vector3d(double.PositiveInfinity, double.PositiveInfinity, double.PositiveInfinity);
        return false;
    }

    /// <summary>
    /// The first point at which a sphere of radius <paramref name="radius"/> moving from <paramref name="origin"/>
    /// along the unit <paramref name="direction"/> touches the shape where its parameters put it, within
    /// <paramref name="maxDistance"/> (a ray for radius 0).
    /// </summary>
    /// <remarks>
    /// The default marches along the ray by the safe steps of the contact search (<see cref="IsConvex"/>): to rounding
    /// for a convex shape, within 1e-12 m of the surface otherwise. A start already within the radius hits at distance 0
    /// with the normal there.
    /// </remarks>
    /// <param name="origin">The start of the sphere's centre, in metres.</param>
    /// <param name="direction">The direction, of unit length.</param>
    /// <param name="radius">The sphere's radius, &gt;= 0.</param>
    /// <param name="maxDistance">How far it moves at most, &gt;= 0.</param>
    /// <param name="distance">Receives how far the centre moved to the touch.</param>
    /// <param name="normal">Receives the surface's outward normal at the touch.</param>
    /// <param name="feature">Receives what of the shape was hit: a triangle's index for meshes and height fields, else -1.</param>
    /// <returns>Whether it touches within <paramref name="maxDistance"/>.</returns>
    public virtual bool Cast(
        Vector3d origin, Vector3d direction, double radius, double maxDistance, out double distance, out Vector3d normal, out int feature)
    {
        feature = -1;
        return ShapeCasts.March(this, origin, direction, radius, maxDistance, out distance, out normal);
    }

    /// <summary>The description with the shape moved by <paramref name="offset"/>, for <see cref="Shape"/> and <see cref="ShapeAt"/>.</summary>
    /// <param name="offset">The translation from where the parameters put the shape.</param>
    /// <returns>What a renderer needs; a shape of your own may describe itself as <see cref="ObstacleKind.Custom"/> with its bounds.</returns>
    protected abstract ObstacleShape Describe(Vector3d offset);

    /// <summary>The translation from the parameters' position to the position at <paramref name="time"/>.</summary>
    internal Vector3d OffsetAt(double time) => (time - _referenceTime) * _velocity;

    /// <summary>
    /// True only when the point is outside the shape and farther than <paramref name="reach"/> from it, phi &gt; reach
    /// (false when unsure, the default): a particle there cannot touch within a move shorter than reach minus its
    /// radius, and the contact stage skips it without asking the exact distance. Meshes answer it without a walk to the
    /// nearest triangle. <paramref name="knownPoint"/> and <paramref name="knownGap"/> carry a fact the shape may use and
    /// set: phi &gt;= knownGap at knownPoint, in the shape's own frame (-infinity: none).
    /// </summary>
    internal virtual bool IsFarOutside(double x, double y, double z, double reach, ref Vector3d knownPoint, ref double knownGap) => false;

    /// <summary>
    /// A step u &gt;= 0 along a path at relative place q, relative velocity w and bend at most <paramref name="bend"/>
    /// within which the gap cannot close (<see cref="ContactSearch"/>), given the gap and its rate at q. Meshes and height
    /// fields override it with the least of their triangles' convex bounds, and may return +infinity once they know the
    /// gap cannot close within <paramref name="limit"/>, the rest of the search's interval.
    /// </summary>
    internal virtual double SafeStep(
        double qx, double qy, double qz, double wx, double wy, double wz, double radius, double gap, double rate, double bend, double limit) =>
        IsConvex ? ContactSearch.SafeStep(gap, rate, bend) : ContactSearch.LipschitzStep(gap, rate, Math.Sqrt((wx * wx) + (wy * wy) + (wz * wz)), bend);
}
