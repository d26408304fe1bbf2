using System;
using ParticlePhysics.Constraints;
using ParticlePhysics.Forces;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Scenarios;

/// <summary>
/// One mass on a zero-rest-length spring to a fixed anchor at the origin, with linear drag c and gravity:
/// m y'' + c y' + k y = -m g, starting at (0, y0, 0) with velocity (0, v0, 0). Equilibrium y = -m g / k.
/// </summary>
/// <remarks>
/// Exact: with z = y + m g / k, a = c / (2 m), w0^2 = k / m and q = v0 + a z0,
/// z(t) = e^(-a t) (z0 C(t) + q S(t)), where (C, S) = (cos wd t, sin(wd t) / wd) under-damped (wd^2 = w0^2 - a^2),
/// (1, t) critically damped, and (cosh s t, sinh(s t) / s) over-damped (s^2 = a^2 - w0^2). Without a spring
/// (k = 0) it is a free fall with drag.
/// </remarks>
public sealed class MassSpringDamperScenario : IExactSolution
{
    /// <summary>The contract's default time step, in seconds.</summary>
    public const double DefaultTimeStep = 0.01;

    /// <summary>The contract's default duration, in seconds.</summary>
    public const double DefaultDuration = 20;

    private double _mass = 1;
    private double _stiffness = 1;
    private double _damping = 0.1;
    private double _y0;
    private double _v0;
    private double _gravity = Forces.Gravity.StandardAcceleration;

    /// <summary>m, in kg (default 1).</summary>
    public double Mass { get => _mass; set { Guard.Mass(value, nameof(Mass)); _mass = value; } }

    /// <summary>k, in N/m (default 1): a finite number &gt;= 0.</summary>
    public double Stiffness { get => _stiffness; set { Guard.NonNegativeFinite(value, nameof(Stiffness)); _stiffness = value; } }

    /// <summary>c, the linear drag on the particle, in N s/m (default 0.1): a finite number &gt;= 0.</summary>
    public double Damping { get => _damping; set { Guard.NonNegativeFinite(value, nameof(Damping)); _damping = value; } }

    /// <summary>The starting height y0, in m (default 0).</summary>
    public double Y0 { get => _y0; set { Guard.Finite(value, nameof(Y0)); _y0 = value; } }

    /// <summary>The starting vertical velocity v0, in m/s (default 0).</summary>
    public double V0 { get => _v0; set { Guard.Finite(value, nameof(V0)); _v0 = value; } }

    /// <summary>g, in m/s^2 (default 9.81): a finite number &gt;= 0.</summary>
    public double Gravity { get => _gravity; set { Guard.NonNegativeFinite(value, nameof(Gravity)); _gravity = value; } }

    /// <summary>The damping ratio zeta = c / (2 sqrt(k m)): below 1 under-damped, 1 critical, above 1 over-damped.</summary>
    public double DampingRatio => _damping / (2 * Math.Sqrt(_stiffness * _mass));

    /// <summary>Builds the particle system: the particle, its anchored spring, drag and gravity (and the spring's projection for xpbd).</summary>
    public ParticleWorld Build()
    {
        var system = new ParticleWorld(1);
        var particle = system.AddParticle(new Vector3d(0, _y0, 0), new Vector3d(0, _v0, 0), _mass);
        var spring = new ZeroLengthSprings(system);
        spring.AddAnchored(particle, Vector3d.Zero, _stiffness);
        system.AddForce(spring);
        system.AddForce(new LinearDrag(_damping));
        system.AddForce(Forces.Gravity.Down(_gravity));
        system.AddConstraints(new SpringProjection(spring)); // how xpbd steps the spring
        return system;
    }

    /// <inheritdoc />
    public void ExactState(double time, Span<double> state)
    {
        var (y, v) = _stiffness == 0.0 ? WithoutSpring(time) : Oscillator(time);
        state.Slice(0, 6).Clear();
        state[1] = y;
        state[4] = v;
    }

    private (double Y, double V) Oscillator(double t)
    {
        var a = _damping / (2 * _mass);
        var w0Squared = _stiffness / _mass;
        var equilibrium = -_mass * _gravity / _stiffness;
        var z0 = _y0 - equilibrium;
        var q = _v0 + (a * z0);
        var discriminant = (a * a) - w0Squared;
        double z, dz;
        if (discriminant < 0)
        {
            var wd = Math.Sqrt(-discriminant);
            double c = Math.Cos(wd * t), s = Math.Sin(wd * t), decay = Math.Exp(-a * t);
            z = decay * ((z0 * c) + (q * s / wd));
            dz = (-a * z) + (decay * ((-z0 * wd * s) + (q * c)));
        }
        else if (discriminant == 0)
        {
            var decay = Math.Exp(-a * t);
            z = decay * (z0 + (q * t));
            dz = (-a * z) + (decay * q);
        }
        else
        {
            var s = Math.Sqrt(discriminant);
            if (s * t < 1)
            {
                double ch = Math.Cosh(s * t), sh = Math.Sinh(s * t), decay = Math.Exp(-a * t);
                z = decay * ((z0 * ch) + (q * sh / s));
                dz = (-a * z) + (decay * ((z0 * s * sh) + (q * ch)));
            }
            else
            {
                // e^(-a t) cosh(s t) and e^(-a t) sinh(s t) as sums of two exponentials, which cannot overflow.
                double slow = Math.Exp((s - a) * t), fast = Math.Exp(-(s + a) * t);
                z = 0.5 * (((z0 + (q / s)) * slow) + ((z0 - (q / s)) * fast));
                dz = (-a * z) + (0.5 * (((z0 * s) + q) * slow + ((q - (z0 * s)) * fast)));
            }
        }

        return (equilibrium + z, dz);
    }

    private (double Y, double V) WithoutSpring(double t)
    {
        if (_damping == 0.0)
        {
            return (_y0 + (_v0 * t) - (0.5 * _gravity * t * t), _v0 - (_gravity * t));
        }

        var tau = _mass / _damping;
        var terminal = -_gravity * tau;
        var decayed = -ExpMinusOne.Of(-t / tau);
        return (_y0 + (terminal * t) + ((_v0 - terminal) * tau * decayed), terminal + ((_v0 - terminal) * (1 - decayed)));
    }
}
