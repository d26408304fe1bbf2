using System;
using System.Globalization;
using ParticlePhysics.Contacts;

namespace ParticlePhysics.Scenarios;

/// <summary>
/// The contract's head-on collision: particle 0 (mass m1) at (-1, 0, 0) moving at (v1, 0, 0) and particle 1 (mass m2)
/// at (1, 0, 0) moving at (v2, 0, 0), both of radius r, restitution e; gravity g (default 0) on both.
/// </summary>
/// <remarks>
/// Exact: when v1 &gt; v2 they touch at t* = (2 - 2 r) / (v1 - v2) and leave with
/// v1' = (m1 v1 + m2 v2 - m2 e (v1 - v2)) / (m1 + m2), v2' = (m1 v1 + m2 v2 + m1 e (v1 - v2)) / (m1 + m2); the x
/// positions are piecewise linear, and gravity moves both alike (y = -g t^2 / 2), which does not change their relative
/// motion.
/// </remarks>
public sealed class CollisionScenario : IExactSolution
{
    /// <summary>The contract's default time step, in seconds.</summary>
    public const double DefaultTimeStep = 0.001;

    /// <summary>The contract's default duration, in seconds.</summary>
    public const double DefaultDuration = 2;

    private double _m1 = 1, _m2 = 1, _v1 = 1, _v2 = -1, _radius = 0.1, _restitution = 1, _gravity;

    /// <summary>m1, in kg (default 1).</summary>
    public double Mass1 { get => _m1; set { Guard.Mass(value, nameof(Mass1)); _m1 = value; } }

    /// <summary>m2, in kg (default 1).</summary>
    public double Mass2 { get => _m2; set { Guard.Mass(value, nameof(Mass2)); _m2 = value; } }

    /// <summary>v1, in m/s (default 1).</summary>
    public double Velocity1 { get => _v1; set { Guard.Finite(value, nameof(Velocity1)); _v1 = value; } }

    /// <summary>v2, in m/s (default -1).</summary>
    public double Velocity2 { get => _v2; set { Guard.Finite(value, nameof(Velocity2)); _v2 = value; } }

    /// <summary>r, in m (default 0.1), less than 1 so that they start apart.</summary>
    public double Radius { get => _radius; set { Guard.NonNegativeFinite(value, nameof(Radius)); _radius = value; } }

    /// <summary>e, 0 to 1 (default 1: elastic).</summary>
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

    /// <summary>g, in m/s^2 (default 0: no gravity).</summary>
    public double Gravity { get => _gravity; set { Guard.NonNegativeFinite(value, nameof(Gravity)); _gravity = value; } }

    /// <summary>t* = (2 - 2 r) / (v1 - v2) when v1 &gt; v2, else infinity.</summary>
    public double ContactTime => _v1 > _v2 ? (2.0 - (2.0 * _radius)) / (_v1 - _v2) : double.PositiveInfinity;

    /// <summary>v1' = (m1 v1 + m2 v2 - m2 e (v1 - v2)) / (m1 + m2).</summary>
    public double FinalVelocity1 => ((_m1 * _v1) + (_m2 * _v2) - (_m2 * _restitution * (_v1 - _v2))) / (_m1 + _m2);

    /// <summary>v2' = (m1 v1 + m2 v2 + m1 e (v1 - v2)) / (m1 + m2).</summary>
    public double FinalVelocity2 => ((_m1 * _v1) + (_m2 * _v2) + (_m1 * _restitution * (_v1 - _v2))) / (_m1 + _m2);

    /// <summary>Builds the world: two particles with radius r, gravity if g &gt; 0, and a contact set that makes them collide.</summary>
    /// <exception cref="ArgumentException">r &gt;= 1: the particles would start touching.</exception>
    public ParticleWorld Build()
    {
        if (!(_radius < 1.0))
        {
            throw new ArgumentException(string.Format(
                CultureInfo.InvariantCulture, "radius {0:R} must be less than 1: the particles start 2 m apart.", _radius), nameof(Radius));
        }

        var world = new ParticleWorld(2);
        world.AddParticle(new Vector3d(-1, 0, 0), new Vector3d(_v1, 0, 0), _m1);
        world.AddParticle(new Vector3d(1, 0, 0), new Vector3d(_v2, 0, 0), _m2);
        world.SetRadius(0, _radius);
        world.SetRadius(1, _radius);
        if (_gravity > 0.0)
        {
            world.AddForce(Forces.Gravity.Down(_gravity));
        }

        world.AddConstraints(new ContactSet { ParticleCollisions = true, ParticleRestitution = _restitution });
        return world;
    }

    /// <inheritdoc />
    public void ExactState(double time, Span<double> state)
    {
        state.Slice(0, 12).Clear();
        var contact = ContactTime;
        double x1, x2, u1, u2;
        if (time <= contact)
        {
            x1 = -1.0 + (_v1 * time);
            x2 = 1.0 + (_v2 * time);
            u1 = _v1;
            u2 = _v2;
        }
        else
        {
            u1 = FinalVelocity1;
            u2 = FinalVelocity2;
            x1 = -1.0 + (_v1 * contact) + (u1 * (time - contact));
            x2 = 1.0 + (_v2 * contact) + (u2 * (time - contact));
        }

        var y = -0.5 * _gravity * time * time;
        var vy = -_gravity * time;
        state[0] = x1;
        state[1] = y;
        state[3] = x2;
        state[4] = y;
        state[6] = u1;
        state[7] = vy;
        state[9] = u2;
        state[10] = vy;
    }
}
