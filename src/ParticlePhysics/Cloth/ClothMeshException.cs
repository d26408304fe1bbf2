using System;

namespace ParticlePhysics.Cloth;

/// <summary>What is wrong with a mesh that a cloth cannot be made of.</summary>
public enum ClothMeshProblem
{
    /// <summary>The arrays' lengths are not whole vertices or triangles, or there is no triangle.</summary>
    Shape,

    /// <summary>A vertex has a coordinate that is not finite.</summary>
    NonFiniteVertex,

    /// <summary>A triangle names a vertex the mesh does not have.</summary>
    MissingVertex,

    /// <summary>A triangle names one vertex (or one welded particle) twice, or has no area.</summary>
    DegenerateTriangle,

    /// <summary>A vertex no triangle uses.</summary>
    UnusedVertex,

    /// <summary>Two vertices at one position while welding is off.</summary>
    DuplicateVertex,
}

/// <summary>
/// A mesh a cloth cannot be made of (<see cref="WeldedMesh"/>): the message says which vertex or triangle and why, and
/// the properties say it for a program (the scene loader turns them into a JSON path).
/// </summary>
public sealed class ClothMeshException : ArgumentException
{
    /// <summary>Creates the exception.</summary>
    /// <param name="problem">What is wrong.</param>
    /// <param name="triangle">The triangle concerned, or -1.</param>
    /// <param name="vertex">The vertex concerned, or -1.</param>
    /// <param name="message">The whole sentence.</param>
    public ClothMeshException(ClothMeshProblem problem, int triangle, int vertex, string message)
        : base(message)
    {
        Problem = problem;
        Triangle = triangle;
        Vertex = vertex;
    }

    /// <summary>What is wrong.</summary>
    public ClothMeshProblem Problem { get; }

    /// <summary>The triangle concerned (its index in the triangle list), or -1.</summary>
    public int Triangle { get; }

    /// <summary>The vertex concerned (its index in the vertex list), or -1.</summary>
    public int Vertex { get; }
}
