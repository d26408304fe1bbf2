using System;

namespace ParticlePhysics.Aerodynamics;

/// <summary>
/// The air a cloth moves in (<see cref="TriangleAerodynamics"/>): its density, its mean velocity (the wind), the drag
/// and lift coefficients of a flat plate in it, and an optional deterministic <see cref="Aerodynamics.Gust"/>. Every
/// property can be changed between steps; one air can serve several cloths.
/// </summary>
public sealed class Air
{
    /// <summary>The density of air at sea level and 15 degrees C, 1.225 kg/m^3, rounded as the scene contract's default: 1.2.</summary>
    public const double StandardDensity = 1.2;

    private double _density = StandardDensity;
    private Vector3d _velocity;
    private double _drag = 1.0;
    private double _lift;

    /// <summary>Still air of density 1.2 kg/m^3, C_d = 1 and C_l = 0.</summary>
    public Air()
    {
    }

    /// <summary>Air of the given density (kg/m^3), velocity (m/s), drag and lift coefficients.</summary>
    public Air(double density, Vector3d velocity, double dragCoefficient = 1.0, double liftCoefficient = 0.0)
    {
        Density = density;
        Velocity = velocity;
        DragCoefficient = dragCoefficient;
        LiftCoefficient = liftCoefficient;
    }

    /// <summary>rho, kg/m^3: finite and &gt;= 0 (0: no aerodynamic force).</summary>
    public double Density
    {
        get => _density;
        set
        {
            Guard.NonNegativeFinite(value, nameof(Density));
            _density = value;
        }
    }

    /// <summary>The mean velocity of the air (the wind), m/s.</summary>
    public Vector3d Velocity
    {
        get => _velocity;
        set
        {
            Guard.Finite(value, nameof(Velocity));
            _velocity = value;
        }
    }

    /// <summary>C_d, the pressure-drag coefficient of a flat plate (finite, &gt;= 0; about 1.2 for a plate face-on).</summary>
    public double DragCoefficient
    {
        get => _drag;
        set
        {
            Guard.NonNegativeFinite(value, nameof(DragCoefficient));
            _drag = value;
        }
    }

    /// <summary>C_l, the lift coefficient (finite, &gt;= 0).</summary>
    public double LiftCoefficient
    {
        get => _lift;
        set
        {
            Guard.NonNegativeFinite(value, nameof(LiftCoefficient));
            _lift = value;
        }
    }

    /// <summary>A gust added to <see cref="Velocity"/>, or null for a steady wind.</summary>
    public Gust? Gust { get; set; }

    /// <summary>The air's velocity at <paramref name="time"/> and <paramref name="position"/>: the wind plus the gust, m/s.</summary>
    public Vector3d VelocityAt(double time, Vector3d position) =>
        Gust is { } gust ? _velocity + gust.VelocityAt(time, position) : _velocity;
}
