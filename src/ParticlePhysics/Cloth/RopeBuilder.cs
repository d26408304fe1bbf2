using System;
using System.Collections.Generic;
using ParticlePhysics.Constraints;
using ParticlePhysics.Forces;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Cloth;

/// <summary>How a rope resists stretching.</summary>
public enum RopeStretch
{
    /// <summary>A spring of stiffness k on every segment (<see cref="SpringNetwork"/>).</summary>
    Springs,

    /// <summary>A rod on every segment (<see cref="RodNetwork"/>): the rope keeps its length exactly.</summary>
    Inextensible,
}

/// <summary>
/// Builds a rope along a polyline of points: its particles (mass lumped by segment length, as a cloth's by area),
/// stretch as springs or inextensible rods, and Euler-Bernoulli bending of rigidity EI in N m^2
/// (<see cref="RopeBending"/>), which converges to beam theory as the points get closer.
/// </summary>
/// <remarks>
/// The forces, in the order they are added: the springs, the bending, linear drag and (<see cref="Build"/> only)
/// gravity; the constraint sets: the springs' projection, the bending's projection (both for xpbd), the rods.
/// </remarks>
public sealed class RopeBuilder
{
    private readonly double[] _points;
    private readonly List<int> _pins = new();
    private double _mass = 1.0, _stiffness = 1000.0, _damping = 0.1, _rigidity, _radius, _drag = 0.0;
    private double _gravity = Forces.Gravity.StandardAcceleration;
    private RopeStretch _stretch = RopeStretch.Springs;

    /// <summary>A rope through <paramref name="points"/> (at least 2, finite, consecutive points distinct), in order.</summary>
    public RopeBuilder(ReadOnlySpan<Vector3d> points)
    {
        var list = points.ToArray();
        if (list.Length < 2)
        {
            throw new ArgumentException($"A rope needs at least 2 points; got {list.Length}.", nameof(points));
        }

        _points = new double[3 * list.Length];
        for (var i = 0; i < list.Length; i++)
        {
            if (!list[i].IsFinite)
            {
                throw new ArgumentException($"Point {i} is at {list[i]}: every coordinate must be finite.", nameof(points));
            }

            if (i > 0 && !((list[i] - list[i - 1]).Length > 0))
            {
                throw new ArgumentException($"Points {i - 1} and {i} are at one position: a segment needs a length.", nameof(points));
            }

            _points[3 * i] = list[i].X;
            _points[(3 * i) + 1] = list[i].Y;
            _points[(3 * i) + 2] = list[i].Z;
        }
    }

    /// <summary>The number of points (particles).</summary>
    public int PointCount => _points.Length / 3;

    /// <summary>The rope's length as given, m.</summary>
    public double Length
    {
        get
        {
            var length = 0.0;
            for (var i = 1; i < PointCount; i++)
            {
                length += (Point(i) - Point(i - 1)).Length;
            }

            return length;
        }
    }

    /// <summary>The total mass, kg (default 1), lumped by segment length: each segment gives half its mass to each end.</summary>
    public double TotalMass
    {
        get => _mass;
        set
        {
            Guard.Mass(value, nameof(TotalMass));
            _mass = value;
        }
    }

    /// <summary>How the rope resists stretching (default <see cref="RopeStretch.Springs"/>).</summary>
    public RopeStretch Stretch
    {
        get => _stretch;
        set
        {
            if (value is not (RopeStretch.Springs or RopeStretch.Inextensible))
            {
                throw new ArgumentOutOfRangeException(nameof(Stretch), value, "Stretch must be Springs or Inextensible.");
            }

            _stretch = value;
        }
    }

    /// <summary>Each segment's spring stiffness k, N/m (default 1000).</summary>
    public double SpringStiffness
    {
        get => _stiffness;
        set
        {
            Guard.NonNegativeFinite(value, nameof(SpringStiffness));
            _stiffness = value;
        }
    }

    /// <summary>Each segment's spring damping c, N s/m (default 0.1).</summary>
    public double SpringDamping
    {
        get => _damping;
        set
        {
            Guard.NonNegativeFinite(value, nameof(SpringDamping));
            _damping = value;
        }
    }

    /// <summary>The bending rigidity EI, N m^2 (default 0: none).</summary>
    public double BendingRigidity
    {
        get => _rigidity;
        set
        {
            Guard.NonNegativeFinite(value, nameof(BendingRigidity));
            _rigidity = value;
        }
    }

    /// <summary>Each particle's collision radius, m (default 0).</summary>
    public double Radius
    {
        get => _radius;
        set
        {
            Guard.NonNegativeFinite(value, nameof(Radius));
            _radius = value;
        }
    }

    /// <summary>
    /// The linear drag lambda on every particle of the rope, N s/m (default 0); xpbd and the explicit integrators take
    /// it explicitly (stable while h lambda / m &lt; 2).
    /// </summary>
    public double Drag
    {
        get => _drag;
        set
        {
            Guard.NonNegativeFinite(value, nameof(Drag));
            _drag = value;
        }
    }

    /// <summary>g, in m/s^2, pointing down -y (default 9.81); used by <see cref="Build"/> only.</summary>
    public double Gravity
    {
        get => _gravity;
        set
        {
            Guard.NonNegativeFinite(value, nameof(Gravity));
            _gravity = value;
        }
    }

    /// <summary>The points pinned.</summary>
    public IReadOnlyList<int> Pins => _pins;

    /// <summary>Pins point <paramref name="point"/>.</summary>
    /// <returns>This builder.</returns>
    public RopeBuilder Pin(int point)
    {
        Guard.ParticleIndex(point, PointCount, nameof(point));
        _pins.Add(point);
        return this;
    }

    /// <summary>Each point's mass, kg: half the mass of each segment it ends.</summary>
    public double[] ParticleMasses()
    {
        var masses = new double[PointCount];
        var perLength = _mass / Length;
        for (var i = 1; i < PointCount; i++)
        {
            var half = 0.5 * perLength * (Point(i) - Point(i - 1)).Length;
            masses[i - 1] += half;
            masses[i] += half;
        }

        return masses;
    }

    /// <summary>Builds the rope alone in a new world, with drag and gravity.</summary>
    public ParticleRope Build()
    {
        var masses = Validate(0);
        return Add(new ParticleWorld(PointCount), masses, addGravity: true);
    }

    /// <summary>Adds the rope to a world that may hold other bodies (no gravity: one per world). Checked first: a rejected call changes nothing.</summary>
    public ParticleRope AddTo(ParticleWorld world)
    {
        Guard.NotNull(world, nameof(world));
        world.ThrowIfStepping();
        var masses = Validate(world.Count);
        return Add(world, masses, addGravity: false);
    }

    /// <summary>
    /// Adds only the particles (for hosts that share one generator per family: the scene loader), with the given
    /// velocities (one per point, or empty) and pins; returns the world's index of point 0.
    /// </summary>
    public int AddParticles(ParticleWorld world, ReadOnlySpan<Vector3d> velocities)
    {
        Guard.NotNull(world, nameof(world));
        world.ThrowIfStepping();
        if (velocities.Length != 0 && velocities.Length != PointCount)
        {
            throw new ArgumentException($"velocities must hold one per point ({PointCount}) or none; it holds {velocities.Length}.", nameof(velocities));
        }

        var masses = Validate(world.Count);
        return AddParticles(world, masses, velocities.ToArray());
    }

    /// <summary>
    /// Adds the rope's elements for particles from <paramref name="firstParticle"/> on: springs (for
    /// <see cref="RopeStretch.Springs"/>) or rods (<see cref="RopeStretch.Inextensible"/>), and the bending when EI &gt; 0.
    /// </summary>
    public void AddElements(int firstParticle, SpringNetwork? springs, RodNetwork? rods, QuadraticBending? bending)
    {
        for (var i = 1; i < PointCount; i++)
        {
            var length = (Point(i) - Point(i - 1)).Length;
            if (_stretch == RopeStretch.Springs)
            {
                Guard.NotNull(springs, nameof(springs));
                springs!.Add(firstParticle + i - 1, firstParticle + i, _stiffness, length, _damping);
            }
            else
            {
                Guard.NotNull(rods, nameof(rods));
                rods!.AddRod(firstParticle + i - 1, firstParticle + i, length);
            }
        }

        if (_rigidity > 0.0)
        {
            Guard.NotNull(bending, nameof(bending));
            RopeBending.AddPolyline(bending!, _points, firstParticle, _rigidity);
        }
    }

    private ParticleRope Add(ParticleWorld world, double[] masses, bool addGravity)
    {
        var first = AddParticles(world, masses, Array.Empty<Vector3d>());
        var springs = _stretch == RopeStretch.Springs ? new SpringNetwork(world) : null;
        var rods = _stretch == RopeStretch.Inextensible ? new RodNetwork(world) : null;
        var bending = _rigidity > 0.0 ? new QuadraticBending(world) : null;
        AddElements(first, springs, rods, bending);
        var particles = new int[PointCount];
        for (var i = 0; i < particles.Length; i++)
        {
            particles[i] = first + i;
        }

        var drag = addGravity ? new LinearDrag(_drag) : new LinearDrag(_drag, world, particles);
        var gravity = addGravity ? Forces.Gravity.Down(_gravity) : null;
        if (springs is not null)
        {
            world.AddForce(springs);
        }

        if (bending is not null)
        {
            world.AddForce(bending);
        }

        world.AddForce(drag);
        if (gravity is not null)
        {
            world.AddForce(gravity);
        }

        var springProjection = springs is null ? null : new SpringProjection(springs);
        var bendingProjection = bending is null ? null : new BendingProjection(bending);
        if (springProjection is not null)
        {
            world.AddConstraints(springProjection);
        }

        if (bendingProjection is not null)
        {
            world.AddConstraints(bendingProjection);
        }

        if (rods is not null)
        {
            world.AddConstraints(rods);
        }

        return new ParticleRope(world, first, PointCount, springs, springProjection, rods, bending, bendingProjection, drag, gravity);
    }

    private int AddParticles(ParticleWorld world, double[] masses, Vector3d[] velocities)
    {
        var first = world.Count;
        for (var i = 0; i < masses.Length; i++)
        {
            var index = world.AddParticle(Point(i), velocities.Length == 0 ? Vector3d.Zero : velocities[i], masses[i]);
            if (_radius > 0)
            {
                world.SetRadius(index, _radius);
            }
        }

        foreach (var pin in _pins)
        {
            if (!world.IsPinned(first + pin))
            {
                world.Pin(first + pin, world.GetVelocity(first + pin));
            }
        }

        return first;
    }

    private double[] Validate(int existing)
    {
        if (existing > ParticleWorld.MaxParticles - PointCount)
        {
            throw new InvalidOperationException(
                $"The world holds {existing} particles; {PointCount} more would pass its limit of {ParticleWorld.MaxParticles}.");
        }

        var masses = ParticleMasses();
        for (var i = 0; i < masses.Length; i++)
        {
            if (!DoubleChecks.IsFinite(masses[i]) || !(masses[i] >= Guard.SmallestMass))
            {
                throw new InvalidOperationException(
                    $"Point {i} of the rope would have mass {Guard.Format(masses[i])} kg: every particle needs a positive mass with a finite inverse "
                    + $"(at least {Guard.Format(Guard.SmallestMass)} kg); give the rope more mass.");
            }
        }

        return masses;
    }

    private Vector3d Point(int i) => new(_points[3 * i], _points[(3 * i) + 1], _points[(3 * i) + 2]);
}
