using System;
using System.Globalization;
using ParticlePhysics.Cloth;

namespace ParticlePhysics.Scenarios;

/// <summary>
/// The course's square cloth: n x n particles on a grid of spacing r in the plane y = 0 (particle (row, col) has
/// index row * n + col and starts at rest at (col r, 0, row r)), joined by structural, shear and bend springs of
/// stiffness k and axial damping c, with linear drag and gravity, held by two corners by default.
/// </summary>
public sealed class ClothScenario
{
    /// <summary>The contract's default time step, in seconds.</summary>
    public const double DefaultTimeStep = 0.001;

    /// <summary>The contract's default duration, in seconds.</summary>
    public const double DefaultDuration = 5;

    /// <summary>The largest number of particles per side the builder accepts (4 million particles in all).</summary>
    public const int MaxParticlesPerSide = ClothBuilder.MaxSide;

    private double _size = 1, _resolution = 0.1, _mass = 1, _stiffness = 50, _damping = 0.05, _drag = 0.01;
    private double _gravity = Forces.Gravity.StandardAcceleration;

    /// <summary>The side S of the square, in m (default 1).</summary>
    public double Size { get => _size; set { Guard.PositiveFinite(value, nameof(Size)); _size = value; } }

    /// <summary>The spacing r between neighbours, in m (default 0.1); S / r must be a whole number.</summary>
    public double Resolution { get => _resolution; set { Guard.PositiveFinite(value, nameof(Resolution)); _resolution = value; } }

    /// <summary>The total mass M, in kg (default 1), split evenly over the particles.</summary>
    public double Mass { get => _mass; set { Guard.Mass(value, nameof(Mass)); _mass = value; } }

    /// <summary>The stiffness k of every spring, in N/m (default 50).</summary>
    public double Stiffness { get => _stiffness; set { Guard.NonNegativeFinite(value, nameof(Stiffness)); _stiffness = value; } }

    /// <summary>The axial damping c of every spring, in N s/m (default 0.05).</summary>
    public double Damping { get => _damping; set { Guard.NonNegativeFinite(value, nameof(Damping)); _damping = value; } }

    /// <summary>The linear drag lambda on every particle, in N s/m (default 0.01).</summary>
    public double Drag { get => _drag; set { Guard.NonNegativeFinite(value, nameof(Drag)); _drag = value; } }

    /// <summary>g, in m/s^2 (default 9.81).</summary>
    public double Gravity { get => _gravity; set { Guard.NonNegativeFinite(value, nameof(Gravity)); _gravity = value; } }

    /// <summary>Which particles are pinned (default: the two corners of row 0).</summary>
    public ClothPinning Pinning { get; set; } = ClothPinning.Corners;

    /// <summary>
    /// The number n of particles per side: S / r + 1.
    /// </summary>
    /// <exception cref="ArgumentException">S / r is not a whole number (tolerance 1e-9), or n is too large.</exception>
    public int ParticlesPerSide
    {
        get
        {
            var ratio = _size / _resolution;
            var whole = Math.Round(ratio);
            if (Math.Abs(ratio - whole) > 1e-9 || whole < 1)
            {
                throw new ArgumentException(string.Format(
                    CultureInfo.InvariantCulture,
                    "resolution {0:R} does not divide size {1:R}: size / resolution = {2:R} must be a whole number >= 1.",
                    _resolution,
                    _size,
                    ratio), nameof(Resolution));
            }

            if (whole + 1 > MaxParticlesPerSide)
            {
                throw new ArgumentException(string.Format(
                    CultureInfo.InvariantCulture,
                    "size / resolution = {0:R} gives {1} particles per side; at most {2} are allowed.",
                    ratio,
                    whole + 1,
                    MaxParticlesPerSide), nameof(Resolution));
            }

            return (int)whole + 1;
        }
    }

    /// <summary>The number of springs of an n x n cloth: 2 n (n - 1) structural, 2 (n - 1)^2 shear, 2 n (n - 2) bend.</summary>
    public static int SpringCount(int n) => (2 * n * (n - 1)) + (2 * (n - 1) * (n - 1)) + (2 * n * Math.Max(0, n - 2));

    /// <summary>Builds the cloth: particles, one spring network, drag and gravity.</summary>
    public ParticleWorld Build() => CreateBuilder().Build().System;

    /// <summary>
    /// A <see cref="ClothBuilder"/> set to this scenario's cloth, to build it with its mesh or change what the course
    /// does not (spring families, extra pins, a rectangle).
    /// </summary>
    public ClothBuilder CreateBuilder()
    {
        var n = ParticlesPerSide;
        var builder = new ClothBuilder
        {
            Rows = n,
            Columns = n,
            Spacing = _resolution,
            TotalMass = _mass,
            Drag = _drag,
            Gravity = _gravity,
            Pinning = Pinning,
        };
        return builder.WithSprings(_stiffness, _damping);
    }
}
