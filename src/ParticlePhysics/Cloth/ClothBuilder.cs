using System;
using System.Collections.Generic;
using ParticlePhysics.Constraints;
using ParticlePhysics.Forces;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Cloth;

/// <summary>
/// Builds a rectangular cloth of <see cref="Rows"/> x <see cref="Columns"/> particles joined by springs: the course's
/// square cloth (<see cref="Scenarios.ClothScenario"/> is built with it) and any other. Particle (row, col) has local index
/// row * columns + col and starts at rest at <see cref="Origin"/> + (col r, 0, row r): the cloth lies flat, facing +y.
/// </summary>
/// <remarks>
/// Springs, in the order they are added (for each particle in index order): structural (row, col)-(row, col + 1) and
/// (row, col)-(row + 1, col), rest length r; shear (row, col)-(row + 1, col + 1) and (row, col + 1)-(row + 1, col),
/// rest length r sqrt(2); bend (row, col)-(row, col + 2) and (row, col)-(row + 2, col), rest length 2 r. Each family
/// can be switched off or given its own stiffness and damping. Then linear drag and gravity, in that order, and a
/// <see cref="SpringProjection"/> of the springs, which projects them under xpbd (and does nothing otherwise).
/// </remarks>
public sealed class ClothBuilder
{
    /// <summary>The largest number of particles a cloth may have: 2048 x 2048, the world's own limit.</summary>
    public const int MaxParticles = ParticleWorld.MaxParticles;

    /// <summary>The most particles along a side (rows or columns): 2048, 4 million particles in a square cloth.</summary>
    public const int MaxSide = 2048;

    private readonly List<int> _pins = new();
    private ClothPinning _pinning = ClothPinning.Corners;
    private int _rows = 11, _columns = 11;
    private double _spacing = 0.1, _mass = 1, _drag = 0.01, _gravity = Forces.Gravity.StandardAcceleration;
    private Vector3d _origin;

    /// <summary>The number of rows, at least 2 (default 11). Rows run along +z.</summary>
    public int Rows
    {
        get => _rows;
        set
        {
            CheckSide(value, nameof(Rows));
            _rows = value;
        }
    }

    /// <summary>The number of columns, at least 2 (default 11). Columns run along +x.</summary>
    public int Columns
    {
        get => _columns;
        set
        {
            CheckSide(value, nameof(Columns));
            _columns = value;
        }
    }

    /// <summary>The spacing r between neighbouring particles, in m (default 0.1).</summary>
    public double Spacing
    {
        get => _spacing;
        set
        {
            Guard.PositiveFinite(value, nameof(Spacing));
            _spacing = value;
        }
    }

    /// <summary>The total mass, in kg (default 1), split evenly over the particles.</summary>
    public double TotalMass
    {
        get => _mass;
        set
        {
            Guard.Mass(value, nameof(TotalMass));
            _mass = value;
        }
    }

    /// <summary>The position of particle (0, 0), in m (default the origin).</summary>
    public Vector3d Origin
    {
        get => _origin;
        set
        {
            Guard.Finite(value, nameof(Origin));
            _origin = value;
        }
    }

    /// <summary>The linear drag lambda on every particle of the cloth, in N s/m (default 0.01).</summary>
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

    /// <summary>The pins of a preset (default: the two corners of row 0); <see cref="Pin(int)"/> adds more.</summary>
    public ClothPinning Pinning
    {
        get => _pinning;
        set
        {
            CheckPinning(value);
            _pinning = value;
        }
    }

    /// <summary>The structural springs, to the right and down neighbours (default k = 50 N/m, c = 0.05 N s/m).</summary>
    public ClothSpringFamily Structural { get; } = new(50, 0.05);

    /// <summary>The shear springs, along both diagonals of each cell (default k = 50 N/m, c = 0.05 N s/m).</summary>
    public ClothSpringFamily Shear { get; } = new(50, 0.05);

    /// <summary>The bend springs, to the neighbours two away (default k = 50 N/m, c = 0.05 N s/m).</summary>
    public ClothSpringFamily Bend { get; } = new(50, 0.05);

    /// <summary>The particles pinned besides <see cref="Pinning"/>'s, by local index.</summary>
    public IReadOnlyList<int> ExtraPins => _pins;

    /// <summary>The number of particles: rows x columns.</summary>
    public int ParticleCount => _rows * _columns;

    /// <summary>Sets all three spring families' stiffness and damping (and switches them on).</summary>
    /// <returns>This builder.</returns>
    public ClothBuilder WithSprings(double stiffness, double damping)
    {
        foreach (var family in new[] { Structural, Shear, Bend })
        {
            family.Stiffness = stiffness;
            family.Damping = damping;
            family.Enabled = true;
        }

        return this;
    }

    /// <summary>Pins particle (row, column) as well.</summary>
    /// <returns>This builder.</returns>
    public ClothBuilder Pin(int row, int column)
    {
        if ((uint)row >= (uint)_rows || (uint)column >= (uint)_columns)
        {
            throw new ArgumentOutOfRangeException(
                nameof(row), $"(row, column) must lie in the {_rows} x {_columns} grid; got ({row}, {column}).");
        }

        _pins.Add((row * _columns) + column);
        return this;
    }

    /// <summary>Pins the particle of local index <paramref name="particle"/> (row * columns + col) as well.</summary>
    /// <returns>This builder.</returns>
    public ClothBuilder Pin(int particle)
    {
        Guard.ParticleIndex(particle, ParticleCount, nameof(particle));
        _pins.Add(particle);
        return this;
    }

    /// <summary>Pins every particle of a row (row 0 is the edge the <see cref="ClothPinning.Edge"/> preset pins).</summary>
    /// <returns>This builder.</returns>
    public ClothBuilder PinRow(int row)
    {
        for (var col = 0; col < _columns; col++)
        {
            Pin(row, col);
        }

        return this;
    }

    /// <summary>Pins every particle of a column.</summary>
    /// <returns>This builder.</returns>
    public ClothBuilder PinColumn(int column)
    {
        for (var row = 0; row < _rows; row++)
        {
            Pin(row, column);
        }

        return this;
    }

    /// <summary>Forgets the pins added with <see cref="Pin(int)"/> and its kin (the <see cref="Pinning"/> preset stays).</summary>
    public void ClearExtraPins() => _pins.Clear();

    /// <summary>
    /// Builds the cloth alone in a new particle system: its particles, one spring network, linear drag and gravity,
    /// added in that order.
    /// </summary>
    /// <exception cref="InvalidOperationException">A setting that no cloth can have (see <see cref="AddTo"/>).</exception>
    public ParticleCloth Build()
    {
        Validate(0);
        var system = new ParticleWorld(ParticleCount);
        var springs = AddParticlesAndSprings(system, 0);
        var drag = new LinearDrag(_drag);
        var gravity = Forces.Gravity.Down(_gravity);
        system.AddForce(springs);
        system.AddForce(drag);
        system.AddForce(gravity);
        var projection = new SpringProjection(springs);
        system.AddConstraints(projection);
        return new ParticleCloth(system, _rows, _columns, 0, springs, drag, gravity, projection);
    }

    /// <summary>
    /// Adds the cloth to a system that may hold other bodies: its particles after the existing ones, its spring
    /// network, and linear drag on its own particles. No gravity is added: the system's own gravity, if any, acts on
    /// the cloth (add one <see cref="Forces.Gravity"/> per system).
    /// Everything is checked before anything is added: a rejected call leaves <paramref name="system"/> as it was.
    /// </summary>
    /// <exception cref="InvalidOperationException">
    /// A pin outside the grid, a particle mass (<see cref="TotalMass"/> / <see cref="ParticleCount"/>) too small to
    /// have a finite inverse, a spacing that puts a particle or a rest length beyond the finite numbers, or more
    /// particles than the world can take.
    /// </exception>
    public ParticleCloth AddTo(ParticleWorld system)
    {
        Guard.NotNull(system, nameof(system));
        Validate(system.Count);
        var first = system.Count;
        var springs = AddParticlesAndSprings(system, first);
        var particles = new int[ParticleCount];
        for (var i = 0; i < particles.Length; i++)
        {
            particles[i] = first + i;
        }

        var drag = new LinearDrag(_drag, system, particles);
        system.AddForce(springs);
        system.AddForce(drag);
        var projection = new SpringProjection(springs);
        system.AddConstraints(projection);
        return new ParticleCloth(system, _rows, _columns, first, springs, drag, null, projection);
    }

    private static void CheckSide(int value, string name)
    {
        if (value < 2 || value > MaxSide)
        {
            throw new ArgumentOutOfRangeException(name, value, $"{name} must be 2 to {MaxSide}; got {value}.");
        }
    }

    private static void CheckPinning(ClothPinning value)
    {
        if (value is not (ClothPinning.Corners or ClothPinning.Edge or ClothPinning.None))
        {
            throw new ArgumentOutOfRangeException(
                nameof(Pinning), value, $"Pinning must be Corners, Edge or None; got {(int)value}.");
        }
    }

    /// <summary>Everything that could make adding the cloth fail halfway, checked before anything is added.</summary>
    private void Validate(int existingParticles)
    {
        CheckPinning(_pinning);
        foreach (var pin in _pins)
        {
            if (pin >= ParticleCount)
            {
                throw new InvalidOperationException(
                    $"Pin {pin} lies outside the {_rows} x {_columns} cloth (the grid shrank after it was pinned).");
            }
        }

        if (existingParticles > ParticleWorld.MaxParticles - ParticleCount)
        {
            throw new InvalidOperationException(
                $"The world holds {existingParticles} particles; {ParticleCount} more would pass its limit of {ParticleWorld.MaxParticles}.");
        }

        var particleMass = _mass / ParticleCount;
        try
        {
            Guard.Mass(particleMass, "particle mass");
        }
        catch (ArgumentOutOfRangeException e)
        {
            throw new InvalidOperationException(
                $"TotalMass {Guard.Format(_mass)} kg split over {ParticleCount} particles gives {Guard.Format(particleMass)} kg "
                + $"each, below the smallest mass with a finite inverse ({Guard.Format(Guard.SmallestMass)} kg).",
                e);
        }

        // The farthest particle (computed as AddParticlesAndSprings computes it) and every rest length must be finite:
        // r sqrt(2) of the shear springs can overflow on a 2 x 2 cloth whose corners are still finite (2 r of the bend
        // springs cannot: a side long enough for them has a particle at 2 r from the origin).
        var far = new Vector3d(_origin.X + ((_columns - 1) * _spacing), _origin.Y, _origin.Z + ((_rows - 1) * _spacing));
        if (!far.IsFinite || !DoubleChecks.IsFinite(_spacing * Math.Sqrt(2)))
        {
            throw new InvalidOperationException(
                $"Spacing {Guard.Format(_spacing)} m from Origin {_origin} puts the far corner of the {_rows} x {_columns} "
                + $"cloth at {far}, or a shear spring's rest length r sqrt(2) beyond the finite numbers.");
        }
    }

    private SpringNetwork AddParticlesAndSprings(ParticleWorld system, int first)
    {
        int rows = _rows, columns = _columns;
        var r = _spacing;
        var particleMass = _mass / (rows * columns);
        for (var row = 0; row < rows; row++)
        {
            for (var col = 0; col < columns; col++)
            {
                system.AddParticle(new Vector3d(_origin.X + (col * r), _origin.Y, _origin.Z + (row * r)), particleMass);
            }
        }

        switch (_pinning)
        {
            case ClothPinning.Corners:
                system.Pin(first);
                system.Pin(first + columns - 1);
                break;
            case ClothPinning.Edge:
                for (var col = 0; col < columns; col++)
                {
                    system.Pin(first + col);
                }

                break;
            case ClothPinning.None:
                break;
            default:
                throw new ArgumentOutOfRangeException(nameof(Pinning), Pinning, "Pinning must be Corners, Edge or None.");
        }

        foreach (var pin in _pins)
        {
            system.Pin(first + pin);
        }

        var springs = new SpringNetwork(system);
        var diagonal = r * Math.Sqrt(2);
        for (var row = 0; row < rows; row++)
        {
            for (var col = 0; col < columns; col++)
            {
                var i = first + (row * columns) + col;
                if (Structural.Enabled && col + 1 < columns)
                {
                    springs.Add(i, i + 1, Structural.Stiffness, r, Structural.Damping);
                }

                if (Structural.Enabled && row + 1 < rows)
                {
                    springs.Add(i, i + columns, Structural.Stiffness, r, Structural.Damping);
                }

                if (Shear.Enabled && row + 1 < rows && col + 1 < columns)
                {
                    springs.Add(i, i + columns + 1, Shear.Stiffness, diagonal, Shear.Damping);
                    springs.Add(i + 1, i + columns, Shear.Stiffness, diagonal, Shear.Damping);
                }

                if (Bend.Enabled && col + 2 < columns)
                {
                    springs.Add(i, i + 2, Bend.Stiffness, 2 * r, Bend.Damping);
                }

                if (Bend.Enabled && row + 2 < rows)
                {
                    springs.Add(i, i + (2 * columns), Bend.Stiffness, 2 * r, Bend.Damping);
                }
            }
        }

        return springs;
    }
}
