using System;
using System.Globalization;
using ParticlePhysics.Contacts;
using ParticlePhysics.Forces;

namespace ParticlePhysics.Scenarios;

/// <summary>
/// The contract's bouncing ball: one particle of mass m and radius R dropped from (0, h, 0) with velocity (vx0, 0, 0)
/// onto the ground plane y = 0 (restitution e, friction mu), under gravity and linear drag.
/// </summary>
/// <remarks>
/// Exact without drag: the first impact at t1 = sqrt(2 (h - R) / g) at speed u1 = g t1; rebound n leaves at e^n u1,
/// flies 2 e^n u1 / g and peaks at R + e^(2n) (h - R); impact n + 1 is at t1 + 2 u1 (e + ... + e^n) / g, and the bounces
/// end at T = t1 (1 + e) / (1 - e), after which the ball rests at y = R. Impact n takes
/// min(|vx|, mu (1 + e) e^(n-1) u1) off |vx|; once resting, the ball decelerates at mu g until it stops.
/// </remarks>
public sealed class BouncingBallScenario : IExactSolution
{
    /// <summary>The contract's default time step, in seconds.</summary>
    public const double DefaultTimeStep = 0.001;

    /// <summary>The contract's default duration, in seconds.</summary>
    public const double DefaultDuration = 5;

    // The exact solution follows at most this many bounces (beyond them the rebound is far below any rounding).
    private const int MaxBounces = 100_000;

    private double _mass = 1, _radius, _height = 1, _vx0, _restitution = 0.8, _friction, _drag;
    private double _gravity = Forces.Gravity.StandardAcceleration;

    /// <summary>m, in kg (default 1).</summary>
    public double Mass { get => _mass; set { Guard.Mass(value, nameof(Mass)); _mass = value; } }

    /// <summary>R, in m (default 0: a point).</summary>
    public double Radius { get => _radius; set { Guard.NonNegativeFinite(value, nameof(Radius)); _radius = value; } }

    /// <summary>The starting height h of the centre, in m (default 1; at least <see cref="Radius"/>).</summary>
    public double Height { get => _height; set { Guard.Finite(value, nameof(Height)); _height = value; } }

    /// <summary>The starting horizontal velocity vx0, in m/s (default 0).</summary>
    public double Vx0 { get => _vx0; set { Guard.Finite(value, nameof(Vx0)); _vx0 = value; } }

    /// <summary>The ground's restitution e, 0 to 1 (default 0.8).</summary>
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

    /// <summary>The ground's friction mu (default 0).</summary>
    public double Friction { get => _friction; set { Guard.NonNegativeFinite(value, nameof(Friction)); _friction = value; } }

    /// <summary>The linear drag lambda, in N s/m (default 0; the exact solution holds only without it).</summary>
    public double Drag { get => _drag; set { Guard.NonNegativeFinite(value, nameof(Drag)); _drag = value; } }

    /// <summary>g, in m/s^2 (default 9.81).</summary>
    public double Gravity { get => _gravity; set { Guard.NonNegativeFinite(value, nameof(Gravity)); _gravity = value; } }

    /// <summary>True when there is an exact solution: without drag.</summary>
    public bool HasExactSolution => _drag == 0.0;

    /// <summary>t1 = sqrt(2 (h - R) / g): the first impact (infinite without gravity).</summary>
    public double FirstImpactTime => _gravity > 0.0 ? Math.Sqrt(2.0 * (_height - _radius) / _gravity) : double.PositiveInfinity;

    /// <summary>u1 = g t1: the speed of the first impact.</summary>
    public double FirstImpactSpeed => Math.Sqrt(2.0 * _gravity * (_height - _radius));

    /// <summary>T = t1 (1 + e) / (1 - e): when the bounces end (infinite for e = 1).</summary>
    public double RestTime => _restitution < 1.0 ? FirstImpactTime * (1.0 + _restitution) / (1.0 - _restitution) : double.PositiveInfinity;

    /// <summary>The exact apex after rebound n (n = 0: the drop height): R + e^(2n) (h - R).</summary>
    public double ApexHeight(int bounce) => _radius + (Math.Pow(_restitution, 2 * bounce) * (_height - _radius));

    /// <summary>The exact time of impact n &gt;= 1: t1 + 2 u1 (e + e^2 + ... + e^(n-1)) / g.</summary>
    public double ImpactTime(int impact)
    {
        if (impact < 1)
        {
            throw new ArgumentOutOfRangeException(nameof(impact), impact, "Impacts are numbered from 1.");
        }

        var e = _restitution;
        var sum = e == 1.0 ? impact - 1.0 : e * (1.0 - Math.Pow(e, impact - 1)) / (1.0 - e);
        return FirstImpactTime + (2.0 * FirstImpactSpeed * sum / _gravity);
    }

    /// <summary>Builds the world: the particle, gravity, drag, and a contact set with the ground plane.</summary>
    /// <exception cref="ArgumentException">The ball starts below the ground (h &lt; R).</exception>
    public ParticleWorld Build()
    {
        if (_height < _radius)
        {
            throw new ArgumentException(string.Format(
                CultureInfo.InvariantCulture,
                "height {0:R} is below the radius {1:R}: the ball would start inside the ground.",
                _height,
                _radius), nameof(Height));
        }

        var world = new ParticleWorld(1);
        world.AddParticle(new Vector3d(0, _height, 0), new Vector3d(_vx0, 0, 0), _mass);
        world.SetRadius(0, _radius);
        world.AddForce(Forces.Gravity.Down(_gravity));
        world.AddForce(new LinearDrag(_drag));
        var contacts = new ContactSet();
        contacts.Add(PlaneObstacle.Ground(_restitution, _friction));
        world.AddConstraints(contacts);
        return world;
    }

    /// <inheritdoc />
    /// <remarks>Exact without drag; with drag it is the drag-free motion (see <see cref="HasExactSolution"/>).</remarks>
    public void ExactState(double time, Span<double> state)
    {
        state.Slice(0, 6).Clear();
        var g = _gravity;
        var t1 = FirstImpactTime;
        var vx = _vx0;
        if (!(time > t1))
        {
            state[0] = vx * time;
            state[1] = _height - (0.5 * g * time * time);
            state[3] = vx;
            state[4] = -g * time;
            return;
        }

        var x = vx * t1;
        var impact = t1;
        var speed = FirstImpactSpeed; // the speed of the coming impact
        for (var n = 1; n <= MaxBounces; n++)
        {
            var rebound = _restitution * speed;
            vx = Slowed(vx, _friction * (1.0 + _restitution) * speed);
            var flight = 2.0 * rebound / g;
            if (rebound > 0.0 && time < impact + flight)
            {
                var tau = time - impact;
                state[0] = x + (vx * tau);
                state[1] = _radius + (rebound * tau) - (0.5 * g * tau * tau);
                state[3] = vx;
                state[4] = rebound - (g * tau);
                return;
            }

            x += vx * flight;
            impact += flight;
            speed = rebound;
            if (!(flight > 0.0) || impact >= RestTime)
            {
                break;
            }
        }

        // Resting on the ground from T on: sliding friction mu g until it stops.
        var rest = Math.Max(0.0, time - Math.Min(impact, RestTime));
        var deceleration = _friction * g;
        var stop = deceleration > 0.0 ? Math.Abs(vx) / deceleration : double.PositiveInfinity;
        var sliding = Math.Min(rest, stop);
        var sign = Math.Sign(vx);
        state[0] = x + (vx * sliding) - (sign * 0.5 * deceleration * sliding * sliding);
        state[1] = _radius;
        state[3] = rest < stop ? vx - (sign * deceleration * rest) : 0.0;
    }

    private static double Slowed(double v, double cut) => Math.Sign(v) * Math.Max(0.0, Math.Abs(v) - cut);
}
