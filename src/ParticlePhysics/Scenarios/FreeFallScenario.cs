using System;
using ParticlePhysics.Forces;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Scenarios;

/// <summary>
/// The course's free fall with viscous friction: one particle of mass m released at rest at (0, h, 0) under
/// gravity and linear drag lambda. Exact, with tau = m / lambda:
/// vy(t) = -g tau (1 - e^(-t/tau)); y(t) = h - g tau t + g tau^2 (1 - e^(-t/tau)); without drag vy = -g t and
/// y = h - g t^2 / 2.
/// </summary>
public sealed class FreeFallScenario : IExactSolution
{
    /// <summary>The contract's default time step, in seconds.</summary>
    public const double DefaultTimeStep = 0.01;

    /// <summary>The contract's default duration, in seconds.</summary>
    public const double DefaultDuration = 10;

    private double _mass = 0.01;
    private double _drag = 0.01;
    private double _height = 300;
    private double _gravity = Forces.Gravity.StandardAcceleration;

    /// <summary>m, in kg (default 0.01): a positive finite number.</summary>
    public double Mass { get => _mass; set { Guard.Mass(value, nameof(Mass)); _mass = value; } }

    /// <summary>lambda, in N s/m (default 0.01): a finite number &gt;= 0.</summary>
    public double Drag { get => _drag; set { Guard.NonNegativeFinite(value, nameof(Drag)); _drag = value; } }

    /// <summary>The starting height h, in m (default 300).</summary>
    public double Height { get => _height; set { Guard.Finite(value, nameof(Height)); _height = value; } }

    /// <summary>g, in m/s^2 (default 9.81): a finite number &gt;= 0.</summary>
    public double Gravity { get => _gravity; set { Guard.NonNegativeFinite(value, nameof(Gravity)); _gravity = value; } }

    /// <summary>Builds the particle system: one particle, gravity and linear drag.</summary>
    public ParticleWorld Build()
    {
        var system = new ParticleWorld(1);
        system.AddParticle(new Vector3d(0, _height, 0), _mass);
        system.AddForce(Forces.Gravity.Down(_gravity));
        system.AddForce(new LinearDrag(_drag));
        return system;
    }

    /// <inheritdoc />
    public void ExactState(double time, Span<double> state)
    {
        double y, vy;
        if (_drag == 0.0)
        {
            vy = -_gravity * time;
            y = _height - (0.5 * _gravity * time * time);
        }
        else
        {
            // 1 - e^(-s) = -expm1(-s), and y = h - g tau^2 (s - (1 - e^(-s))), both without cancellation at small s.
            var tau = _mass / _drag;
            var s = time / tau;
            var decayed = -ExpMinusOne.Of(-s);
            vy = -_gravity * tau * decayed;
            y = _height - (_gravity * tau * tau * (s - decayed));
        }

        state.Slice(0, 6).Clear();
        state[1] = y;
        state[4] = vy;
    }
}
