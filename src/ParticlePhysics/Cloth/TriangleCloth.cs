using System;
using System.Numerics;
using ParticlePhysics.Aerodynamics;
using ParticlePhysics.Constraints;
using ParticlePhysics.Forces;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Cloth;

/// <summary>
/// A cloth built from a mesh by <see cref="MeshClothBuilder"/>: where its particles are in the world, the forces that
/// move it (retune them between steps), its welded mesh, and the per-render-vertex positions and normals a renderer
/// takes, written without allocating.
/// </summary>
public sealed class TriangleCloth
{
    private readonly Vector3[] _particlePositions;
    private readonly Vector3[] _particleNormals;

    internal TriangleCloth(
        ParticleWorld world,
        WeldedMesh mesh,
        int firstParticle,
        SpringNetwork? springs,
        SpringProjection? springProjection,
        TriangleMembrane? membrane,
        MembraneProjection? membraneProjection,
        QuadraticBending? bending,
        BendingProjection? bendingProjection,
        LinearDrag drag,
        TriangleAerodynamics? aerodynamics,
        Gravity? gravity)
    {
        System = world;
        Mesh = mesh;
        FirstParticle = firstParticle;
        Springs = springs;
        SpringProjection = springProjection;
        Membrane = membrane;
        MembraneProjection = membraneProjection;
        Bending = bending;
        BendingProjection = bendingProjection;
        Drag = drag;
        Aerodynamics = aerodynamics;
        Gravity = gravity;
        _particlePositions = new Vector3[mesh.ParticleCount];
        _particleNormals = new Vector3[mesh.ParticleCount];
    }

    /// <summary>The world that holds the cloth.</summary>
    public ParticleWorld System { get; }

    /// <summary>The welded mesh: the maps between render vertices and particles, and the triangles.</summary>
    public WeldedMesh Mesh { get; }

    /// <summary>The world's index of the cloth's particle 0; particle i of the mesh is FirstParticle + i.</summary>
    public int FirstParticle { get; }

    /// <summary>The number of particles (welded vertices).</summary>
    public int ParticleCount => Mesh.ParticleCount;

    /// <summary>The springs (edge springs and those added one by one), or null.</summary>
    public SpringNetwork? Springs { get; }

    /// <summary>The springs as xpbd constraints, or null.</summary>
    public SpringProjection? SpringProjection { get; }

    /// <summary>The membrane, or null.</summary>
    public TriangleMembrane? Membrane { get; }

    /// <summary>The membrane as xpbd constraints, or null.</summary>
    public MembraneProjection? MembraneProjection { get; }

    /// <summary>The bending, or null.</summary>
    public QuadraticBending? Bending { get; }

    /// <summary>The bending as xpbd constraints, or null.</summary>
    public BendingProjection? BendingProjection { get; }

    /// <summary>The linear drag on the cloth's particles.</summary>
    public LinearDrag Drag { get; }

    /// <summary>The air's drag and lift on the cloth's triangles, or null when it was built without an air.</summary>
    public TriangleAerodynamics? Aerodynamics { get; }

    /// <summary>The gravity <see cref="MeshClothBuilder.Build"/> added, or null for a cloth added to an existing world.</summary>
    public Gravity? Gravity { get; }

    /// <summary>The world's index of the particle of render vertex <paramref name="vertex"/>.</summary>
    public int ParticleIndex(int vertex) => FirstParticle + Mesh.ParticleOf(vertex);

    /// <summary>
    /// Attaches the particles of the render vertices listed to a moving body (a character's bone): each is pinned and
    /// follows the body from where it is (<see cref="KinematicBody.Attach"/>); a seam's vertices, or a vertex listed
    /// twice, attach their particle once, and a particle attached to the body already is left as it is.
    /// </summary>
    public void Attach(KinematicBody body, ReadOnlySpan<int> vertices)
    {
        Guard.NotNull(body, nameof(body));
        System.ThrowIfStepping();
        var list = vertices.ToArray();
        foreach (var v in list)
        {
            Guard.ParticleIndex(v, Mesh.VertexCount, nameof(vertices));
        }

        foreach (var v in list)
        {
            var particle = ParticleIndex(v);
            var attached = false;
            foreach (var p in body.Particles)
            {
                attached |= p == particle;
            }

            if (!attached)
            {
                body.Attach(particle);
            }
        }
    }

    /// <summary>
    /// Writes the cloth's positions, rounded to single precision, per render vertex into <paramref name="vertices"/>
    /// (at least <see cref="WeldedMesh.VertexCount"/>): a seam's vertices get their particle's position. Allocates nothing.
    /// </summary>
    public void WriteVertices(Span<Vector3> vertices)
    {
        ReadParticles();
        Mesh.ScatterToVertices(_particlePositions, vertices);
    }

    /// <summary>
    /// Writes the cloth's normals per render vertex into <paramref name="normals"/> (at least
    /// <see cref="WeldedMesh.VertexCount"/>): each particle's area-weighted normal, the same on both sides of a seam.
    /// Allocates nothing.
    /// </summary>
    public void WriteNormals(Span<Vector3> normals)
    {
        ReadParticles();
        Mesh.ComputeParticleNormals(_particlePositions, _particleNormals);
        Mesh.ScatterToVertices(_particleNormals, normals);
    }

    /// <summary>
    /// Writes render vertices and normals from positions per particle that the caller has (interpolated by a
    /// <see cref="Driver.FixedTimestepDriver"/>, for instance): <paramref name="particlePositions"/> holds
    /// <see cref="ParticleCount"/> positions. Allocates nothing.
    /// </summary>
    public void WriteMesh(ReadOnlySpan<Vector3> particlePositions, Span<Vector3> vertices, Span<Vector3> normals)
    {
        Mesh.ComputeParticleNormals(particlePositions, _particleNormals);
        Mesh.ScatterToVertices(particlePositions, vertices);
        Mesh.ScatterToVertices(_particleNormals, normals);
    }

    private void ReadParticles()
    {
        var x = System.Positions.ForReading();
        for (var i = 0; i < _particlePositions.Length; i++)
        {
            var o = 3 * (FirstParticle + i);
            _particlePositions[i] = new Vector3((float)x[o], (float)x[o + 1], (float)x[o + 2]);
        }
    }
}
