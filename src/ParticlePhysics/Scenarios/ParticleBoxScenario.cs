using System;
using ParticlePhysics.Contacts;

namespace ParticlePhysics.Scenarios;

/// <summary>
/// A pile: N particles of radius r dropped into an open box (a floor y = 0 and four walls), under gravity, colliding with
/// each other and with the box. They start at rest on a lattice of spacing 2.2 r, m x m per layer with
/// m = ceil(sqrt(N / L)) for L layers (default 3), the lowest layer at y = 1.1 r, each nudged sideways by up to 0.05 r (a
/// fixed pseudo-random pattern, the same on every run) so that they roll into the hollows of the layer below. The
/// density, and so the work per particle, is the same whatever N. Used by the tests (a settled pile overlaps by less than 1 % of r) and the
/// contact benchmark.
/// </summary>
public sealed class ParticleBoxScenario
{
    private int _count = 1000;
    private int _layers = 3;
    private double _radius = 0.05, _mass = 0.01, _restitution, _friction = 0.3;
    private double _gravity = Forces.Gravity.StandardAcceleration;

    /// <summary>N (default 1000), 1 to <see cref="ParticleWorld.MaxParticles"/>.</summary>
    public int Count
    {
        get => _count;
        set
        {
            if (value < 1 || value > ParticleWorld.MaxParticles)
            {
                throw new ArgumentOutOfRangeException(nameof(Count), value, $"Count must be 1 to {ParticleWorld.MaxParticles}; got {value}.");
            }

            _count = value;
        }
    }

    /// <summary>L, the number of layers they start in (default 3), 1 to 1000.</summary>
    public int Layers
    {
        get => _layers;
        set
        {
            if (value < 1 || value > 1000)
            {
                throw new ArgumentOutOfRangeException(nameof(Layers), value, $"Layers must be 1 to 1000; got {value}.");
            }

            _layers = value;
        }
    }

    /// <summary>r, in m (default 0.05).</summary>
    public double Radius { get => _radius; set { Guard.PositiveFinite(value, nameof(Radius)); _radius = value; } }

    /// <summary>The mass of each particle, in kg (default 0.01).</summary>
    public double Mass { get => _mass; set { Guard.Mass(value, nameof(Mass)); _mass = value; } }

    /// <summary>e between particles and with the box (default 0).</summary>
    public double Restitution
    {
        get => _restitution;
        set
        {
            if (!(value >= 0.0 && value <= 1.0))
            {
                throw new ArgumentOutOfRangeException(nameof(Restitution), value, $"Restitution must be from 0 to 1; got {Guard.Format(value)}.");
            }

            _restitution = value;
        }
    }

    /// <summary>mu between particles and with the box (default 0.3).</summary>
    public double Friction { get => _friction; set { Guard.NonNegativeFinite(value, nameof(Friction)); _friction = value; } }

    /// <summary>g, in m/s^2 (default 9.81).</summary>
    public double Gravity { get => _gravity; set { Guard.NonNegativeFinite(value, nameof(Gravity)); _gravity = value; } }

    /// <summary>m: particles per row of a layer.</summary>
    public int PerRow => (int)Math.Ceiling(Math.Sqrt((double)_count / _layers) - 1e-9);

    /// <summary>The inner width of the box, in m: m rows of spacing 2.2 r.</summary>
    public double Width => PerRow * 2.2 * _radius;

    /// <summary>Builds the world: the particles, gravity, and a contact set with the floor, the four walls and particle collisions.</summary>
    public ParticleWorld Build()
    {
        var m = PerRow;
        var spacing = 2.2 * _radius;
        var world = new ParticleWorld(_count);
        var seed = 0x9E3779B9u;
        for (var i = 0; i < _count; i++)
        {
            var layer = i / (m * m);
            var row = (i / m) % m;
            var column = i % m;
            var jx = Jitter(ref seed);
            var jz = Jitter(ref seed);
            var position = new Vector3d(
                (spacing * (column + 0.5)) + (jx * 0.05 * _radius),
                (spacing * (layer + 0.5)),
                (spacing * (row + 0.5)) + (jz * 0.05 * _radius));
            world.AddParticle(position, _mass);
            world.SetRadius(i, _radius);
        }

        world.AddForce(Forces.Gravity.Down(_gravity));
        var contacts = new ContactSet
        {
            ParticleCollisions = true,
            ParticleRestitution = _restitution,
            ParticleFriction = _friction,
        };
        var width = Width;
        contacts.Add(new PlaneObstacle(Vector3d.Zero, new Vector3d(0, 1, 0), _restitution, _friction));
        contacts.Add(new PlaneObstacle(Vector3d.Zero, new Vector3d(1, 0, 0), _restitution, _friction));
        contacts.Add(new PlaneObstacle(new Vector3d(width, 0, 0), new Vector3d(-1, 0, 0), _restitution, _friction));
        contacts.Add(new PlaneObstacle(Vector3d.Zero, new Vector3d(0, 0, 1), _restitution, _friction));
        contacts.Add(new PlaneObstacle(new Vector3d(0, 0, width), new Vector3d(0, 0, -1), _restitution, _friction));
        world.AddConstraints(contacts);
        return world;
    }

    /// <summary>A number in [-1, 1) from a 32-bit xorshift generator: the same sequence on every platform.</summary>
    private static double Jitter(ref uint state)
    {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        return (state / 2147483648.0) - 1.0;
    }
}
