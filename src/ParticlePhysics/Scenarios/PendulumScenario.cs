using System;
using ParticlePhysics.Constraints;
using ParticlePhysics.Forces;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Scenarios;

/// <summary>
/// A mass m on a rod of length L to an anchor at the origin, released at rest at angle theta0 from the downward
/// vertical in the x-y plane, at (L sin theta0, -L cos theta0, 0), under gravity and linear drag (default none).
/// The rod is a hard constraint (<see cref="RodNetwork"/>), not a stiff spring.
/// </summary>
/// <remarks>
/// Exact without drag: with k = sin(theta0 / 2), w = sqrt(g / L) and K(k) the complete elliptic integral of the first
/// kind, sin(theta(t) / 2) = k sn(K - w t, k), so theta = 2 asin(k sn(u)) and, since cos(theta / 2) = dn(u),
/// theta' = -2 k w cn(u) (u = K - w t). The period is 4 K(k) / w (2.367842 s at 90 degrees on 1 m, 2 pi / w =
/// 2.006067 s for small swings). Derivation: energy conservation gives theta'^2 = 4 w^2 (k^2 - sin^2(theta / 2));
/// the substitution sin(theta / 2) = k sin(phi) turns it into phi' = w sqrt(1 - k^2 sin^2 phi), whose solution is
/// sin(phi) = sn(K - w t) from the turning point.
/// </remarks>
public sealed class PendulumScenario : IExactSolution
{
    /// <summary>The contract's default time step, in seconds.</summary>
    public const double DefaultTimeStep = 0.001;

    /// <summary>The contract's default duration, in seconds.</summary>
    public const double DefaultDuration = 10;

    private double _mass = 1, _length = 1, _angle = 90, _drag;
    private double _gravity = Forces.Gravity.StandardAcceleration;

    /// <summary>m, in kg (default 1).</summary>
    public double Mass { get => _mass; set { Guard.Mass(value, nameof(Mass)); _mass = value; } }

    /// <summary>L, the rod's length, in m (default 1).</summary>
    public double Length { get => _length; set { Guard.PositiveFinite(value, nameof(Length)); _length = value; } }

    /// <summary>theta0, the starting angle from the downward vertical, in degrees: between 0 and 180 exclusive (default 90).</summary>
    public double Angle
    {
        get => _angle;
        set
        {
            if (!(value > 0.0 && value < 180.0))
            {
                throw new ArgumentOutOfRangeException(
                    nameof(Angle), value, $"Angle must be between 0 and 180 degrees, exclusive; got {Guard.Format(value)}.");
            }

            _angle = value;
        }
    }

    /// <summary>The linear drag lambda on the bob, in N s/m (default 0; the exact solution holds without it).</summary>
    public double Drag { get => _drag; set { Guard.NonNegativeFinite(value, nameof(Drag)); _drag = value; } }

    /// <summary>g, in m/s^2 (default 9.81).</summary>
    public double Gravity { get => _gravity; set { Guard.NonNegativeFinite(value, nameof(Gravity)); _gravity = value; } }

    /// <summary>True when <see cref="ExactState"/> holds: without drag.</summary>
    public bool HasExactSolution => _drag == 0.0;

    /// <summary>The modulus k = sin(theta0 / 2).</summary>
    public double Modulus => Math.Sin(0.5 * _angle * Math.PI / 180.0);

    /// <summary>w = sqrt(g / L), in rad/s.</summary>
    public double AngularFrequency => Math.Sqrt(_gravity / _length);

    /// <summary>The exact period 4 K(k) / w, in s (infinite without gravity).</summary>
    public double Period => 4.0 * JacobiElliptic.CompleteK(Modulus) / AngularFrequency;

    /// <summary>The period of small swings, 2 pi / w, in s.</summary>
    public double SmallSwingPeriod => 2.0 * Math.PI / AngularFrequency;

    /// <summary>Builds the world: the bob, its rod to the origin, gravity and drag.</summary>
    public ParticleWorld Build()
    {
        var world = new ParticleWorld(1);
        var theta = _angle * Math.PI / 180.0;
        var bob = world.AddParticle(new Vector3d(_length * Math.Sin(theta), -_length * Math.Cos(theta), 0), _mass);
        var rods = new RodNetwork(world);
        rods.AddAnchoredRod(bob, Vector3d.Zero, _length);
        world.AddForce(Forces.Gravity.Down(_gravity));
        world.AddForce(new LinearDrag(_drag));
        world.AddConstraints(rods);
        return world;
    }

    /// <summary>The exact angle theta(t) from the downward vertical, in radians (positive toward +x), and its rate.</summary>
    /// <exception cref="InvalidOperationException">There is drag: no exact solution.</exception>
    public (double Angle, double Rate) ExactAngle(double time)
    {
        if (!HasExactSolution)
        {
            throw new InvalidOperationException("The pendulum has no exact solution with drag; set Drag to 0.");
        }

        var k = Modulus;
        var w = AngularFrequency;
        var u = JacobiElliptic.CompleteK(k) - (w * time);
        var (sn, cn, _) = JacobiElliptic.Functions(u, k);
        return (2.0 * Math.Asin(k * sn), -2.0 * k * w * cn);
    }

    /// <summary>The angle from the downward vertical of a bob at (x, y), in radians: atan2(x, -y).</summary>
    public static double AngleOf(Vector3d position) => Math.Atan2(position.X, -position.Y);

    /// <inheritdoc />
    public void ExactState(double time, Span<double> state)
    {
        var (theta, rate) = ExactAngle(time);
        double s = Math.Sin(theta), c = Math.Cos(theta);
        state.Slice(0, 6).Clear();
        state[0] = _length * s;
        state[1] = -_length * c;
        state[3] = _length * c * rate;
        state[4] = _length * s * rate;
    }
}
