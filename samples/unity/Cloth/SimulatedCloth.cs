using System;
using System.IO;
using System.Runtime.InteropServices;
using ParticlePhysics;
using ParticlePhysics.Cloth;
using ParticlePhysics.Driver;
using ParticlePhysics.Integrators;
using ParticlePhysics.Snapshots;
using UnityEngine;
using UnityEngine.Rendering;

/// <summary>
/// A square cloth of ParticlePhysics particles hanging from two corners, stepped at a fixed 60 Hz out of Unity's frame
/// times and drawn through this game object's MeshFilter, with the positions interpolated between the last two steps.
/// Give the game object a MeshRenderer with a double-sided material. Nothing in Update allocates.
/// </summary>
/// <remarks>
/// The Inspector's values are read once, in Start. Implicit Euler takes one step per 60 Hz frame and stays stable at
/// every size the slider allows, whatever the stiffness; an explicit integrator (SemiImplicitEuler) would need about
/// 24 sub-steps of each frame on the 64 x 64 cloth of 1 kg at 50 N/m, and more on a stiffer one.
/// </remarks>
[RequireComponent(typeof(MeshFilter))]
[AddComponentMenu("ParticlePhysics/Simulated Cloth")]
public sealed class SimulatedCloth : MonoBehaviour
{
    /// <summary>The simulated time of one step, in seconds.</summary>
    public const double FixedTimeStep = 1.0 / 60;

    /// <summary>The most steps one frame runs: a frame that falls further behind drops the rest of its time.</summary>
    public const int MaxStepsPerFrame = 3;

    /// <summary>The implicit solve's relative tolerance: about a quarter of the iterations of 1e-6, no visible difference.</summary>
    public const double SolverTolerance = 1e-3;

    [Tooltip("Particles along each side: the cloth has this many squared.")]
    [Range(2, 64)]
    public int particlesPerSide = 21;

    [Tooltip("The side of the square, in metres.")]
    [Range(0.1f, 10f)]
    public float sideLength = 1f;

    [Tooltip("The whole cloth's mass, in kilograms, spread evenly over its particles.")]
    [Range(0.01f, 100f)]
    public float totalMass = 1f;

    [Tooltip("The stiffness of every spring, in N/m.")]
    [Range(0f, 1000f)]
    public float stiffness = 50f;

    [Tooltip("The damping of every spring along its axis, in N s/m.")]
    [Range(0f, 1f)]
    public float damping = 0.05f;

    private ParticleCloth _cloth;
    private FixedTimestepDriver _driver;
    private Mesh _mesh;
    private Vector3[] _vertices;   // UnityEngine.Vector3: what Mesh.SetVertices takes
    private Vector3[] _normals;

    /// <summary>The simulated cloth (null before Start): its world, springs and mesh topology.</summary>
    public ParticleCloth Simulation => _cloth;

    /// <summary>The driver that steps it, and interpolates between steps for rendering.</summary>
    public FixedTimestepDriver Driver => _driver;

    private void Start()
    {
        var builder = new ClothBuilder
        {
            Rows = particlesPerSide,
            Columns = particlesPerSide,
            Spacing = (double)sideLength / (particlesPerSide - 1),
            TotalMass = totalMass,
        };
        builder.WithSprings(stiffness, damping);
        _cloth = builder.Build();   // flat in the plane y = 0, corners (0, 0) and (0, n - 1) pinned
        var integrator = new ImplicitEuler { Tolerance = SolverTolerance };
        _driver = new FixedTimestepDriver(_cloth.System, integrator, FixedTimeStep, subSteps: 1, maxStepsPerFrame: MaxStepsPerFrame);

        _vertices = new Vector3[_cloth.ParticleCount];
        _normals = new Vector3[_cloth.ParticleCount];
        _mesh = new Mesh { name = "Simulated cloth" };
        _mesh.MarkDynamic();
        if (_cloth.ParticleCount > 65535)
        {
            _mesh.indexFormat = IndexFormat.UInt32;
        }

        WriteMesh();
        _mesh.SetTriangles(_cloth.Mesh.CreateTriangles(), 0);   // once: the topology never changes
        GetComponent<MeshFilter>().sharedMesh = _mesh;
    }

    private void Update()
    {
        try
        {
            _driver.Advance(Time.deltaTime);   // 0 to MaxStepsPerFrame fixed steps
        }
        catch (SimulationDivergedException e)
        {
            // The world stays at its last good state; stepping again would fail again.
            Debug.LogError("SimulatedCloth stopped: " + e.Message);
            enabled = false;
            return;
        }

        WriteMesh();
    }

    private void OnDestroy()
    {
        if (_mesh != null)
        {
            Destroy(_mesh);
        }
    }

    private void WriteMesh()
    {
        // UnityEngine.Vector3 and System.Numerics.Vector3 are both three consecutive floats: the engine writes into
        // the arrays through a System.Numerics view of them, and the Mesh takes the arrays themselves.
        var vertices = MemoryMarshal.Cast<Vector3, System.Numerics.Vector3>(_vertices.AsSpan());
        var normals = MemoryMarshal.Cast<Vector3, System.Numerics.Vector3>(_normals.AsSpan());
        _driver.InterpolatePositions(_cloth.FirstParticle, _cloth.ParticleCount, vertices);
        _cloth.Mesh.ComputeNormals(vertices, normals);   // area-weighted, normalised
        _mesh.SetVertices(_vertices);
        _mesh.SetNormals(_normals);
        _mesh.RecalculateBounds();
    }

    /// <summary>Moves a particle (a pinned corner, to carry the cloth) to a point in the game object's local space.</summary>
    public void MoveParticle(int row, int column, Vector3 localPosition)
    {
        _cloth.System.SetPosition(_cloth.ParticleIndex(row, column), ToEngine(localPosition));
    }

    /// <summary>A particle's position in the game object's local space, as simulated (not interpolated).</summary>
    public Vector3 ParticlePosition(int row, int column)
    {
        return ToUnity(_cloth.System.GetPosition(_cloth.ParticleIndex(row, column)));
    }

    /// <summary>Writes the cloth's state and its integrator's to a stream: a save game.</summary>
    public void Save(Stream stream)
    {
        SimulationSnapshot.Capture(_cloth.System, _driver.Integrator).WriteTo(stream);
    }

    /// <summary>
    /// Restores what <see cref="Save"/> wrote, into a cloth built with the same Inspector values (the snapshot holds the
    /// state, not the springs). A truncated or corrupted stream throws InvalidDataException, another cloth size
    /// ArgumentException, and the cloth stays as it was.
    /// </summary>
    public void Restore(Stream stream)
    {
        SimulationSnapshot.ReadFrom(stream).RestoreTo(_cloth.System, _driver.Integrator);
        _driver.Reset();
        WriteMesh();
    }

    // The engine computes in doubles, Unity in floats: round only what is drawn. Both are y-up with the same axes.
    private static Vector3 ToUnity(Vector3d p) => new Vector3((float)p.X, (float)p.Y, (float)p.Z);

    private static Vector3d ToEngine(Vector3 v) => new Vector3d(v.x, v.y, v.z);   // exact
}
