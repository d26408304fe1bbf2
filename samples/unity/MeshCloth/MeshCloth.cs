using System;
using System.Runtime.InteropServices;
using ParticlePhysics;
using ParticlePhysics.Cloth;
using ParticlePhysics.Constraints;
using ParticlePhysics.Driver;
using ParticlePhysics.Integrators;
using UnityEngine;
using UnityEngine.Rendering;

/// <summary>
/// Turns this game object's mesh (a flag, a cape, a curtain: any triangle mesh, its UV seams welded) into a
/// ParticlePhysics cloth: a membrane of physical modulus and Poisson's ratio with plate bending, stepped at a fixed
/// 60 Hz out of Unity's frame times, drawn through the MeshFilter with positions interpolated between steps and normals
/// shared across seams. The vertices painted red in the mesh's vertex colours (red at least <see cref="pinThreshold"/>),
/// or listed in <see cref="pinnedVertices"/>, are pinned; with an <see cref="anchor"/> they follow that transform (a
/// character's bone). Nothing in Update allocates.
/// </summary>
/// <remarks>
/// The cloth is simulated in world space, so it falls under world gravity however the game object is placed; the mesh
/// is written back in the object's local space. The Inspector's values are read once, in Start. xpbd with
/// <see cref="substeps"/> substeps per 60 Hz step: the membrane is as stiff as a substep resolves, so a stiffer or finer
/// cloth needs more substeps.
/// </remarks>
[RequireComponent(typeof(MeshFilter))]
[AddComponentMenu("ParticlePhysics/Mesh Cloth")]
public sealed class MeshCloth : MonoBehaviour
{
    /// <summary>The simulated time of one step, in seconds.</summary>
    public const double FixedTimeStep = 1.0 / 60;

    /// <summary>The most steps one frame runs: a frame that falls further behind drops the rest of its time.</summary>
    public const int MaxStepsPerFrame = 3;

    [Tooltip("The pinned vertices follow this transform (a character's bone); empty: they stay where they are.")]
    public Transform anchor;

    [Tooltip("Pin the vertices whose vertex colour has at least this much red.")]
    [Range(0f, 1f)]
    public float pinThreshold = 0.5f;

    [Tooltip("More vertices to pin, by index in the mesh.")]
    public int[] pinnedVertices = new int[0];

    [Tooltip("Mass per area of the fabric, kg/m^2.")]
    [Range(0.01f, 5f)]
    public float density = 0.2f;

    [Tooltip("Young's modulus times thickness, N/m.")]
    [Range(1f, 100000f)]
    public float modulus = 1000f;

    [Tooltip("Poisson's ratio of the membrane.")]
    [Range(0f, 0.49f)]
    public float poisson = 0.3f;

    [Tooltip("Viscosity of the membrane's strain rate, N s/m.")]
    [Range(0f, 10f)]
    public float damping = 0.2f;

    [Tooltip("Flexural rigidity of the plate, N m.")]
    [Range(0f, 0.01f)]
    public float bendingRigidity = 0.0001f;

    [Tooltip("xpbd substeps per 60 Hz step.")]
    [Range(1, 100)]
    public int substeps = 20;

    private TriangleCloth _cloth;
    private FixedTimestepDriver _driver;
    private KinematicBody _body;
    private Mesh _mesh;
    private Vector3[] _particles;   // interpolated particle positions, world space
    private Vector3[] _vertices;    // per render vertex: world space, then local space
    private Vector3[] _normals;

    /// <summary>The simulated cloth (null before Start): its world, forces and welded mesh.</summary>
    public TriangleCloth Simulation => _cloth;

    /// <summary>The driver that steps it.</summary>
    public FixedTimestepDriver Driver => _driver;

    /// <summary>The moving body the pinned vertices are attached to, or null without an anchor.</summary>
    public KinematicBody Body => _body;

    private void Start()
    {
        var source = GetComponent<MeshFilter>().sharedMesh;
        var local = source.vertices;
        var triangles = source.triangles;
        var colors = source.colors;
        var positions = new double[3 * local.Length];
        for (var v = 0; v < local.Length; v++)
        {
            var p = transform.TransformPoint(local[v]);
            positions[3 * v] = p.x;
            positions[(3 * v) + 1] = p.y;
            positions[(3 * v) + 2] = p.z;
        }

        var builder = new MeshClothBuilder(new WeldedMesh(positions, triangles, weld: true))
        {
            AreaDensity = density,
            Modulus = modulus,
            Poisson = poisson,
            MembraneDamping = damping,
            BendingRigidity = bendingRigidity,
        };
        var pins = new System.Collections.Generic.List<int>(pinnedVertices);
        for (var v = 0; v < colors.Length && v < local.Length; v++)
        {
            if (colors[v].r >= pinThreshold)
            {
                pins.Add(v);
            }
        }

        if (anchor == null)
        {
            builder.PinVertices(pins.ToArray());
        }

        _cloth = builder.Build();
        if (anchor != null)
        {
            _body = new KinematicBody(_cloth.System, ToEngine(anchor.position), ToEngine(anchor.rotation));
            _cloth.Attach(_body, pins.ToArray());
        }

        _driver = new FixedTimestepDriver(_cloth.System, new Xpbd(substeps), FixedTimeStep, subSteps: 1, maxStepsPerFrame: MaxStepsPerFrame);
        _particles = new Vector3[_cloth.ParticleCount];
        _vertices = new Vector3[local.Length];
        _normals = new Vector3[local.Length];
        _mesh = new Mesh { name = source.name + " (cloth)" };
        _mesh.MarkDynamic();
        if (local.Length > 65535)
        {
            _mesh.indexFormat = IndexFormat.UInt32;
        }

        WriteMesh();
        _mesh.SetTriangles(triangles, 0);   // once: the render topology never changes
        GetComponent<MeshFilter>().sharedMesh = _mesh;
    }

    private void Update()
    {
        try
        {
            if (_body != null && Time.deltaTime > 0f)
            {
                // The bone's pose at the end of this frame's time: the attached particles move toward it at the velocity
                // that reaches it then, so the cloth sees the bone's motion.
                _body.MoveTo(ToEngine(anchor.position), ToEngine(anchor.rotation), Time.deltaTime);
            }

            _driver.Advance(Time.deltaTime);
        }
        catch (SimulationDivergedException e)
        {
            Debug.LogError("MeshCloth stopped: " + e.Message);
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
        // UnityEngine.Vector3 and System.Numerics.Vector3 are both three consecutive floats: the engine writes through a
        // System.Numerics view of the arrays, and the Mesh takes the arrays themselves.
        var particles = MemoryMarshal.Cast<Vector3, System.Numerics.Vector3>(_particles.AsSpan());
        _driver.InterpolatePositions(_cloth.FirstParticle, _cloth.ParticleCount, particles);
        _cloth.WriteMesh(
            particles,
            MemoryMarshal.Cast<Vector3, System.Numerics.Vector3>(_vertices.AsSpan()),
            MemoryMarshal.Cast<Vector3, System.Numerics.Vector3>(_normals.AsSpan()));
        for (var v = 0; v < _vertices.Length; v++)
        {
            _vertices[v] = transform.InverseTransformPoint(_vertices[v]);
            _normals[v] = transform.InverseTransformDirection(_normals[v]);
        }

        _mesh.SetVertices(_vertices);
        _mesh.SetNormals(_normals);
        _mesh.RecalculateBounds();
    }

    // The engine computes in doubles, Unity in floats: round only what is drawn. Both are y-up with the same axes.
    private static Vector3d ToEngine(Vector3 v) => new Vector3d(v.x, v.y, v.z);   // exact

    private static Rotation3d ToEngine(Quaternion q) => new Rotation3d(q.x, q.y, q.z, q.w);
}
