using System;
using System.Numerics;
using ParticlePhysics.Constraints;
using ParticlePhysics.Forces;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Cloth;

/// <summary>
/// A cloth built by <see cref="ClothBuilder"/>: where its particles are in the system, the force generators that
/// move it (retune them between steps), and its render mesh. (Not named Cloth, which would clash with UnityEngine.Cloth.)
/// </summary>
public sealed class ParticleCloth
{
    internal ParticleCloth(
        ParticleWorld system,
        int rows,
        int columns,
        int firstParticle,
        SpringNetwork springs,
        LinearDrag drag,
        Gravity? gravity,
        SpringProjection projection)
    {
        Projection = projection;
        System = system;
        Rows = rows;
        Columns = columns;
        FirstParticle = firstParticle;
        Springs = springs;
        Drag = drag;
        Gravity = gravity;
        Mesh = new ClothMesh(rows, columns);
    }

    /// <summary>The particle system that holds the cloth.</summary>
    public ParticleWorld System { get; }

    /// <summary>The number of rows of particles.</summary>
    public int Rows { get; }

    /// <summary>The number of columns of particles.</summary>
    public int Columns { get; }

    /// <summary>The system index of particle (0, 0); particle (row, col) is FirstParticle + row * Columns + col.</summary>
    public int FirstParticle { get; }

    /// <summary>The number of particles: rows x columns.</summary>
    public int ParticleCount => Rows * Columns;

    /// <summary>The cloth's springs (structural, shear and bend, in the order the builder documents).</summary>
    public SpringNetwork Springs { get; }

    /// <summary>The springs as xpbd distance constraints (in the world's constraint sets): how xpbd steps the cloth.</summary>
    public SpringProjection Projection { get; }

    /// <summary>The linear drag on the cloth's particles.</summary>
    public LinearDrag Drag { get; }

    /// <summary>The gravity <see cref="ClothBuilder.Build"/> added, or null for a cloth added to an existing system.</summary>
    public Gravity? Gravity { get; }

    /// <summary>The render mesh: a triangle index buffer and vertex normals over the cloth's particles.</summary>
    public ClothMesh Mesh { get; }

    /// <summary>The system index of particle (row, column).</summary>
    public int ParticleIndex(int row, int column)
    {
        if ((uint)row >= (uint)Rows || (uint)column >= (uint)Columns)
        {
            throw new ArgumentOutOfRangeException(
                nameof(row), $"(row, column) must lie in the {Rows} x {Columns} grid; got ({row}, {column}).");
        }

        return FirstParticle + (row * Columns) + column;
    }

    /// <summary>
    /// Writes the cloth's current positions, rounded to single precision, into <paramref name="vertices"/> (at least
    /// <see cref="ParticleCount"/> vectors). Allocates nothing. With a <see cref="Driver.FixedTimestepDriver"/>, use its
    /// <see cref="Driver.FixedTimestepDriver.InterpolatePositions(int, int, Span{Vector3})"/> instead.
    /// </summary>
    public void WriteVertices(Span<Vector3> vertices)
    {
        if (vertices.Length < ParticleCount)
        {
            throw new ArgumentException(
                $"vertices must hold at least {ParticleCount} vectors; it holds {vertices.Length}.", nameof(vertices));
        }

        var x = System.Positions.ForReading();
        for (var i = 0; i < ParticleCount; i++)
        {
            var o = 3 * (FirstParticle + i);
            vertices[i] = new Vector3((float)x[o], (float)x[o + 1], (float)x[o + 2]);
        }
    }
}
