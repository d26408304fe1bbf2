using System;
using ParticlePhysics.Constraints;
using ParticlePhysics.Forces;

namespace ParticlePhysics.Scenarios;

/// <summary>
/// N particles in a row joined by N - 1 rods of length l = L / (N - 1), the first and last pinned at (-D/2, 0, 0) and
/// (D/2, 0, 0); total mass M split evenly; gravity and linear drag on every particle. It starts at rest in a V:
/// particle i at x = -D/2 + i D / (N - 1), y = -min(i, N - 1 - i) sqrt(l^2 - (D / (N - 1))^2), and settles into the
/// discrete catenary (<see cref="DiscreteCatenary"/>).
/// </summary>
public sealed class HangingChainScenario
{
    /// <summary>The contract's default time step, in seconds.</summary>
    public const double DefaultTimeStep = 0.001;

    /// <summary>The contract's default duration, in seconds.</summary>
    public const double DefaultDuration = 20;

    /// <summary>The fewest particles: 3.</summary>
    public const int MinParticles = 3;

    /// <summary>The most particles: 1001.</summary>
    public const int MaxParticles = 1001;

    private int _particles = 11;
    private double _length = 2, _span = 1.5, _mass = 1, _drag = 0.1;
    private double _gravity = Forces.Gravity.StandardAcceleration;

    /// <summary>N, the number of particles: odd, 3 to 1001 (default 11).</summary>
    public int Particles
    {
        get => _particles;
        set
        {
            if (value < MinParticles || value > MaxParticles || value % 2 == 0)
            {
                throw new ArgumentOutOfRangeException(
                    nameof(Particles), value, $"Particles must be an odd whole number from {MinParticles} to {MaxParticles}; got {value}.");
            }

            _particles = value;
        }
    }

    /// <summary>L, the chain's length, in m (default 2).</summary>
    public double Length { get => _length; set { Guard.PositiveFinite(value, nameof(Length)); _length = value; } }

    /// <summary>D, the span between the pins, in m (default 1.5): less than L.</summary>
    public double Span { get => _span; set { Guard.PositiveFinite(value, nameof(Span)); _span = value; } }

    /// <summary>M, the total mass, in kg (default 1).</summary>
    public double Mass { get => _mass; set { Guard.Mass(value, nameof(Mass)); _mass = value; } }

    /// <summary>lambda, the linear drag on every particle, in N s/m (default 0.1).</summary>
    public double Drag { get => _drag; set { Guard.NonNegativeFinite(value, nameof(Drag)); _drag = value; } }

    /// <summary>g, in m/s^2 (default 9.81).</summary>
    public double Gravity { get => _gravity; set { Guard.NonNegativeFinite(value, nameof(Gravity)); _gravity = value; } }

    /// <summary>l = L / (N - 1), the length of each rod, in m.</summary>
    public double RodLength => _length / (_particles - 1);

    /// <summary>The index of the middle particle, (N - 1) / 2: the lowest.</summary>
    public int MiddleParticle => (_particles - 1) / 2;

    /// <summary>Builds the world: the particles in a V, the pinned ends, the rods, drag and gravity.</summary>
    /// <exception cref="ArgumentException">The span is not shorter than the chain.</exception>
    public ParticleWorld Build()
    {
        CheckSpan();
        var n = _particles;
        var l = RodLength;
        var step = _span / (n - 1);
        var drop = Math.Sqrt((l - step) * (l + step));
        var world = new ParticleWorld(n);
        var m = _mass / n;
        for (var i = 0; i < n; i++)
        {
            world.AddParticle(new Vector3d((-0.5 * _span) + (i * step), -Math.Min(i, n - 1 - i) * drop, 0), m);
        }

        world.Pin(0);
        world.Pin(n - 1);
        var rods = new RodNetwork(world);
        for (var i = 0; i + 1 < n; i++)
        {
            rods.AddRod(i, i + 1, l);
        }

        world.AddForce(new LinearDrag(_drag));
        world.AddForce(Forces.Gravity.Down(_gravity));
        world.AddConstraints(rods);
        return world;
    }

    /// <summary>The exact rest shape, the discrete catenary through the two pins (needs gravity).</summary>
    public DiscreteCatenary RestShape()
    {
        CheckSpan();
        return new DiscreteCatenary(_particles, RodLength, _span, _mass / _particles, _gravity, new Vector3d(-0.5 * _span, 0, 0));
    }

    private void CheckSpan()
    {
        if (!(_span < _length))
        {
            throw new ArgumentException(
                $"The span {Guard.Format(_span)} m must be shorter than the chain's length {Guard.Format(_length)} m.", nameof(Span));
        }
    }
}
