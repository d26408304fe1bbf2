using System;
using System.Collections.Generic;
using System.Numerics;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Cloth;

/// <summary>
/// A render mesh (vertices and triangles, as a game has it) checked and welded into the particles of a cloth: vertices
/// at identical positions (a UV seam, a hard edge) become one particle, the first of them giving its index order. It
/// keeps the maps both ways (render vertex to particle, particle to its render vertices) and writes positions and normals
/// back per render vertex, so that a seam's vertices get their particle's position and normal.
/// </summary>
/// <remarks>
/// Refused, with a <see cref="ClothMeshException"/> naming the vertex or triangle: arrays that are not whole vertices
/// or triangles, no triangle, a coordinate that is not finite, a triangle naming a vertex the mesh lacks, a degenerate
/// triangle (two corners on one particle, or an area at most 1e-12 of its longest edge squared), a vertex no triangle
/// uses, and two vertices at one position when welding is off. Edges that three or more triangles share are allowed.
/// Particles are numbered in the order of their first vertex; -0 and 0 are one position.
/// </remarks>
public sealed class WeldedMesh
{
    private const double MinRelativeArea = 1e-12;

    private readonly double[] _vertices;
    private readonly int[] _triangles;
    private readonly int[] _particleTriangles;
    private readonly int[] _particleOfVertex;
    private readonly int[] _firstVertex;
    private readonly int[] _vertexStarts;
    private readonly int[] _verticesByParticle;
    private readonly double[] _particlePositions;

    /// <summary>Checks and welds a mesh.</summary>
    /// <param name="vertices">x, y, z of each render vertex, in m.</param>
    /// <param name="triangles">Three vertex indices per triangle.</param>
    /// <param name="weld">Whether vertices at identical positions become one particle (otherwise they are an error).</param>
    /// <exception cref="ClothMeshException">The mesh cannot be a cloth; the message says where and why.</exception>
    public WeldedMesh(ReadOnlySpan<double> vertices, ReadOnlySpan<int> triangles, bool weld = true)
    {
        if (vertices.Length % 3 != 0 || triangles.Length % 3 != 0)
        {
            throw new ClothMeshException(
                ClothMeshProblem.Shape, -1, -1, $"A mesh needs 3 coordinates per vertex and 3 indices per triangle; got {vertices.Length} coordinates and {triangles.Length} indices.");
        }

        if (triangles.Length == 0)
        {
            throw new ClothMeshException(ClothMeshProblem.Shape, -1, -1, "The mesh has no triangle: a cloth needs at least one.");
        }

        _vertices = vertices.ToArray();
        _triangles = triangles.ToArray();
        var vertexCount = _vertices.Length / 3;
        for (var v = 0; v < vertexCount; v++)
        {
            if (!Position(v).IsFinite)
            {
                throw new ClothMeshException(
                    ClothMeshProblem.NonFiniteVertex, -1, v, $"Vertex {v} is at {Position(v)}: every coordinate must be finite.");
            }
        }

        var used = new bool[vertexCount];
        for (var k = 0; k < _triangles.Length; k++)
        {
            var v = _triangles[k];
            if ((uint)v >= (uint)vertexCount)
            {
                throw new ClothMeshException(
                    ClothMeshProblem.MissingVertex, k / 3, v, $"Triangle {k / 3} names vertex {v}, but the mesh has {vertexCount} vertices (0 to {vertexCount - 1}).");
            }

            used[v] = true;
        }

        for (var v = 0; v < vertexCount; v++)
        {
            if (!used[v])
            {
                throw new ClothMeshException(
                    ClothMeshProblem.UnusedVertex, -1, v, $"Vertex {v} is used by no triangle: remove it, or give it a triangle.");
            }
        }

        // Welding: the first vertex at each position gives the particle, in the order of first vertices.
        _particleOfVertex = new int[vertexCount];
        var firstVertex = new List<int>();
        var byPosition = new Dictionary<(long, long, long), int>();
        for (var v = 0; v < vertexCount; v++)
        {
            var p = Position(v);
            var key = (Bits(p.X), Bits(p.Y), Bits(p.Z));
            if (byPosition.TryGetValue(key, out var particle))
            {
                if (!weld)
                {
                    throw new ClothMeshException(
                        ClothMeshProblem.DuplicateVertex, -1, v, $"Vertices {firstVertex[particle]} and {v} are both at {p}; weld them (weld: true) or move one.");
                }

                _particleOfVertex[v] = particle;
                continue;
            }

            byPosition.Add(key, firstVertex.Count);
            _particleOfVertex[v] = firstVertex.Count;
            firstVertex.Add(v);
        }

        _firstVertex = firstVertex.ToArray();
        var particles = _firstVertex.Length;
        _particlePositions = new double[3 * particles];
        for (var i = 0; i < particles; i++)
        {
            Array.Copy(_vertices, 3 * _firstVertex[i], _particlePositions, 3 * i, 3);
        }

        _vertexStarts = new int[particles + 1];
        for (var v = 0; v < vertexCount; v++)
        {
            _vertexStarts[_particleOfVertex[v] + 1]++;
        }

        for (var i = 0; i < particles; i++)
        {
            _vertexStarts[i + 1] += _vertexStarts[i];
        }

        _verticesByParticle = new int[vertexCount];
        var fill = new int[particles];
        for (var v = 0; v < vertexCount; v++)
        {
            var i = _particleOfVertex[v];
            _verticesByParticle[_vertexStarts[i] + fill[i]++] = v;
        }

        _particleTriangles = new int[_triangles.Length];
        for (var t = 0; t < _triangles.Length / 3; t++)
        {
            int a = _particleOfVertex[_triangles[3 * t]], b = _particleOfVertex[_triangles[(3 * t) + 1]], c = _particleOfVertex[_triangles[(3 * t) + 2]];
            if (a == b || b == c || a == c)
            {
                throw new ClothMeshException(
                    ClothMeshProblem.DegenerateTriangle,
                    t,
                    -1,
                    $"Triangle {t} ({_triangles[3 * t]}, {_triangles[(3 * t) + 1]}, {_triangles[(3 * t) + 2]}) has two corners at one position{(weld ? " (welded into one particle)" : string.Empty)}: it is degenerate.");
            }

            var pa = ParticlePosition(a);
            var e1 = ParticlePosition(b) - pa;
            var e2 = ParticlePosition(c) - pa;
            var longest = Math.Max(e1.LengthSquared, Math.Max(e2.LengthSquared, (e2 - e1).LengthSquared));
            var twiceArea = Vector3d.Cross(e1, e2).Length;
            if (!(twiceArea > 2.0 * MinRelativeArea * longest) || !DoubleChecks.IsFinite(twiceArea) || !DoubleChecks.IsFinite(longest))
            {
                throw new ClothMeshException(
                    ClothMeshProblem.DegenerateTriangle, t, -1, $"Triangle {t} ({_triangles[3 * t]}, {_triangles[(3 * t) + 1]}, {_triangles[(3 * t) + 2]}) has no area: its corners lie on one line.");
            }

            _particleTriangles[3 * t] = a;
            _particleTriangles[(3 * t) + 1] = b;
            _particleTriangles[(3 * t) + 2] = c;
        }
    }

    /// <summary>The number of render vertices.</summary>
    public int VertexCount => _vertices.Length / 3;

    /// <summary>The number of particles: vertices, less those welded into another.</summary>
    public int ParticleCount => _firstVertex.Length;

    /// <summary>The number of triangles.</summary>
    public int TriangleCount => _triangles.Length / 3;

    /// <summary>The triangles by render vertex, as given (Unity's Mesh.SetTriangles takes them).</summary>
    public ReadOnlySpan<int> Triangles => _triangles;

    /// <summary>The triangles by particle (local indices, 0 to <see cref="ParticleCount"/> - 1).</summary>
    public ReadOnlySpan<int> ParticleTriangles => _particleTriangles;

    /// <summary>Each render vertex's particle (local index).</summary>
    public ReadOnlySpan<int> ParticleOfVertex => _particleOfVertex;

    /// <summary>Each particle's first render vertex (whose position it took).</summary>
    public ReadOnlySpan<int> FirstVertexOfParticle => _firstVertex;

    /// <summary>The particles' positions as given, 3 values each.</summary>
    public ReadOnlySpan<double> ParticlePositions => _particlePositions;

    /// <summary>The particle (local index) of render vertex <paramref name="vertex"/>.</summary>
    public int ParticleOf(int vertex)
    {
        Guard.ParticleIndex(vertex, VertexCount, nameof(vertex));
        return _particleOfVertex[vertex];
    }

    /// <summary>The render vertices of particle <paramref name="particle"/>, in increasing order (one unless a seam was welded).</summary>
    public ReadOnlySpan<int> VerticesOf(int particle)
    {
        Guard.ParticleIndex(particle, ParticleCount, nameof(particle));
        return _verticesByParticle.AsSpan(_vertexStarts[particle], _vertexStarts[particle + 1] - _vertexStarts[particle]);
    }

    /// <summary>The position of particle <paramref name="particle"/> as given.</summary>
    public Vector3d ParticlePosition(int particle) =>
        new(_particlePositions[3 * particle], _particlePositions[(3 * particle) + 1], _particlePositions[(3 * particle) + 2]);

    /// <summary>The area of triangle <paramref name="triangle"/> as given, m^2.</summary>
    public double TriangleArea(int triangle)
    {
        if ((uint)triangle >= (uint)TriangleCount)
        {
            throw new ArgumentOutOfRangeException(nameof(triangle), triangle, $"triangle must be 0 to {TriangleCount - 1}; got {triangle}.");
        }

        var a = ParticlePosition(_particleTriangles[3 * triangle]);
        return 0.5 * Vector3d.Cross(ParticlePosition(_particleTriangles[(3 * triangle) + 1]) - a, ParticlePosition(_particleTriangles[(3 * triangle) + 2]) - a).Length;
    }

    /// <summary>Copies each particle's value to its render vertices (a seam's vertices get the same). Allocates nothing.</summary>
    /// <param name="perParticle">At least <see cref="ParticleCount"/> values.</param>
    /// <param name="perVertex">At least <see cref="VertexCount"/> values.</param>
    public void ScatterToVertices(ReadOnlySpan<Vector3> perParticle, Span<Vector3> perVertex)
    {
        if (perParticle.Length < ParticleCount || perVertex.Length < VertexCount)
        {
            throw new ArgumentException(
                $"perParticle must hold {ParticleCount} vectors and perVertex {VertexCount}; they hold {perParticle.Length} and {perVertex.Length}.");
        }

        var source = perParticle.ForReading();
        for (var v = 0; v < _particleOfVertex.Length; v++)
        {
            perVertex[v] = source[_particleOfVertex[v]];
        }
    }

    /// <summary>
    /// Writes the area-weighted, normalised normals of the particles at <paramref name="positions"/> (one per particle):
    /// the sum over a particle's triangles of cross(p1 - p0, p2 - p0), normalised ((0, 1, 0) where that is zero). The
    /// winding is the mesh's own, so the normals point to the side its triangles face. Allocates nothing.
    /// </summary>
    /// <param name="positions">At least <see cref="ParticleCount"/> positions.</param>
    /// <param name="normals">At least <see cref="ParticleCount"/> vectors; must not overlap <paramref name="positions"/>.</param>
    public void ComputeParticleNormals(ReadOnlySpan<Vector3> positions, Span<Vector3> normals)
    {
        var n = ParticleCount;
        if (positions.Length < n || normals.Length < n)
        {
            throw new ArgumentException($"positions and normals must hold {n} vectors each; they hold {positions.Length} and {normals.Length}.");
        }

        if (positions.Overlaps(normals))
        {
            throw new ArgumentException("positions and normals must be distinct buffers.", nameof(normals));
        }

        var p = positions.ForReading();
        normals.Slice(0, n).Clear();
        for (var t = 0; t < _particleTriangles.Length; t += 3)
        {
            int a = _particleTriangles[t], b = _particleTriangles[t + 1], c = _particleTriangles[t + 2];
            var face = Vector3.Cross(p[b] - p[a], p[c] - p[a]);
            normals[a] += face;
            normals[b] += face;
            normals[c] += face;
        }

        for (var i = 0; i < n; i++)
        {
            var length = normals[i].Length();
            normals[i] = length > 0f && !float.IsInfinity(length) ? normals[i] / length : Vector3.UnitY;
        }
    }

    private Vector3d Position(int v) => new(_vertices[3 * v], _vertices[(3 * v) + 1], _vertices[(3 * v) + 2]);

    // -0 and 0 are one position.
    private static long Bits(double value) => BitConverter.DoubleToInt64Bits(value == 0.0 ? 0.0 : value);
}
