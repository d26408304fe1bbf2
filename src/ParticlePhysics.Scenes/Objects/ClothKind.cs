using System;
using System.Collections.Generic;
using System.IO;
using ParticlePhysics.Cloth;
using ParticlePhysics.Scenes.Json;
using ParticlePhysics.Scenes.Kinds;
using ParticlePhysics.Scenes.Meshes;

namespace ParticlePhysics.Scenes.Objects;

/// <summary>
/// <c>cloth</c>: a cloth from any triangle mesh (<see cref="MeshClothBuilder"/>). <c>mesh</c> inline
/// {"vertices": [[x, y, z], ...], "triangles": [[a, b, c], ...]} or {"obj": "file.obj"} (relative to the scene file);
/// its vertices are its particles in file order, <c>weld</c> (default false) merging vertices at one position (the
/// first kept), which are an error otherwise. <c>mass</c> (total, kg, default 1) or <c>density</c> (kg/m^2), lumped a
/// third of each triangle to each corner; <c>stretch</c> {"stiffness": k} (a spring on every edge) or
/// {"modulus": Y, "poisson": nu} (the membrane, default {"modulus": 1000, "poisson": 0.3}), each with "damping"
/// (N s/m: the springs' axial damping, or the membrane's viscosity); <c>bending</c> {"rigidity": D} (N m);
/// <c>velocities</c> (per vertex); <c>pinned</c> (vertex indices); <c>thickness</c> (m: the particles' radius is half
/// of it); <c>aerodynamics</c> (default false: the scene's <c>air</c> pushes on its triangles); <c>selfCollision</c>
/// (default false: no particle comes closer than the thickness to a triangle of the cloth that is not its neighbour,
/// <see cref="Contacts.ClothSelfCollision"/>; needs a thickness). <c>tear</c> arrives with the rest of the issue "cloth in the world".
/// </summary>
internal sealed class ClothKind : ISceneObjectKind
{
    public string Name => "cloth";

    public SceneObject Read(ObjectReader reader, SceneReadContext context)
    {
        foreach (var later in new[] { "tear" })
        {
            if (reader.Get(later) is { } value)
            {
                throw reader.Error(value, reader.PathOf(later), $"not built yet: the cloth's {later} arrives with the issue \"cloth in the world\"", showValue: false);
            }
        }

        var meshReader = reader.Object("mesh", "a cloth's mesh") ?? throw reader.ObjectError(
            "a cloth object needs \"mesh\": {\"vertices\": [[x, y, z], ...], \"triangles\": [[a, b, c], ...]} or {\"obj\": \"file.obj\"}");
        var weld = reader.Boolean("weld", false);
        var (vertices, triangles, source) = ReadMesh(meshReader, context);
        WeldedMesh mesh;
        try
        {
            mesh = new WeldedMesh(vertices, triangles, weld);
        }
        catch (ClothMeshException e)
        {
            throw MeshError(reader, meshReader, source, e);
        }

        var builder = new MeshClothBuilder(mesh);
        if (reader.Has("mass") && reader.Has("density"))
        {
            throw reader.Error(reader.Get("density")!.Value, reader.PathOf("density"), "give \"mass\" (the total, kg) or \"density\" (kg/m^2), not both", showValue: false);
        }

        if (reader.Has("density"))
        {
            builder.AreaDensity = reader.Number("density", null, ValueRule.Positive, "kg/m^2");
        }
        else
        {
            builder.TotalMass = reader.Number("mass", 1.0, ValueRule.Mass, "kg");
        }

        ReadStretch(reader, builder);
        if (reader.Object("bending", "a cloth's bending") is { } bending)
        {
            builder.BendingRigidity = bending.Number("rigidity", null, ValueRule.NonNegative, "N m");
            bending.Finish();
        }

        var velocities = reader.Vectors("velocities", "m/s");
        if (velocities is not null && velocities.Count != mesh.VertexCount)
        {
            throw reader.Error(reader.Get("velocities")!.Value, reader.PathOf("velocities"), $"lists {velocities.Count} velocities for {mesh.VertexCount} vertices; give one per vertex");
        }

        // Copies, not the mesh's spans: this assembly must not index a ReadOnlySpan (its indexer does not bind on Mono).
        var firstVertex = mesh.FirstVertexOfParticle.ToArray();
        var particleVelocities = new Vector3d[velocities is null ? 0 : mesh.ParticleCount];
        for (var i = 0; i < particleVelocities.Length; i++)
        {
            particleVelocities[i] = velocities![firstVertex[i]].Vector;
        }

        foreach (var pin in reader.Indices("pinned") ?? new List<IndexRef>())
        {
            if (pin.Value >= mesh.VertexCount)
            {
                throw reader.Error(pin.Where, pin.Path, $"names no vertex of this cloth: pinned takes its own vertex indices, 0 to {mesh.VertexCount - 1}");
            }

            builder.Pin(pin.Value);
        }

        var thickness = reader.Number("thickness", 0.0, ValueRule.NonNegative, "m");
        var aerodynamics = reader.Boolean("aerodynamics", false);
        var selfCollision = reader.Boolean("selfCollision", false);
        if (selfCollision && !(thickness > 0))
        {
            throw reader.Error(reader.Get("selfCollision")!.Value, reader.PathOf("selfCollision"), "needs the cloth's \"thickness\" (m, above 0): no particle comes closer than it to a triangle of the cloth that is not its neighbour", showValue: false);
        }

        foreach (var m in builder.ParticleMasses())
        {
            if (!(m > 0) || double.IsInfinity(1.0 / m) || double.IsInfinity(m))
            {
                throw reader.ObjectError("its mass spread over its particles leaves one with a mass whose inverse is not finite; give it more mass");
            }
        }

        return new ClothObject(builder, particleVelocities, thickness, aerodynamics, selfCollision);
    }

    private static (double[] Vertices, int[] Triangles, string? Obj) ReadMesh(ObjectReader mesh, SceneReadContext context)
    {
        if (mesh.String("obj") is { } obj)
        {
            var path = Path.Combine(context.Directory, obj);
            TriangleMesh read;
            try
            {
                read = ObjReader.Read(path, obj);
            }
            catch (SceneException e)
            {
                // One line that names the scene file first, as every refusal does, then the OBJ file's own problem.
                throw mesh.Error(mesh.Get("obj")!.Value, mesh.PathOf("obj"), e.Message);
            }

            mesh.Finish();
            return (read.Vertices, read.Triangles, obj);
        }

        var vertices = mesh.Vectors("vertices", "m") ?? throw mesh.ObjectError(
            "a cloth's mesh needs \"vertices\": [[x, y, z], ...] and \"triangles\": [[a, b, c], ...], or \"obj\": \"file.obj\"");
        var trianglesValue = mesh.Get("triangles") ?? throw mesh.ObjectError("a cloth's mesh needs \"triangles\": [[a, b, c], ...] of vertex indices");
        if (trianglesValue.Kind != JsonKind.Array)
        {
            throw mesh.Error(trianglesValue, mesh.PathOf("triangles"), $"must be a list of triangles [a, b, c], not {trianglesValue.KindName()}");
        }

        var triangles = new List<int>(3 * trianglesValue.Count);
        var t = 0;
        foreach (var triangle in trianglesValue.Elements())
        {
            var at = ObjectReader.Index(mesh.PathOf("triangles"), t++);
            if (triangle.Kind != JsonKind.Array || triangle.Count != 3)
            {
                throw mesh.Error(triangle, at, "must be a triangle [a, b, c] of three vertex indices");
            }

            var k = 0;
            foreach (var corner in triangle.Elements())
            {
                if (!corner.IsNumber || corner.Number < 0 || corner.Number != Math.Floor(corner.Number) || corner.Number > int.MaxValue)
                {
                    throw mesh.Error(corner, ObjectReader.Index(at, k), "must be a vertex index: a whole number >= 0");
                }

                triangles.Add((int)corner.Number);
                k++;
            }
        }

        mesh.Finish();
        var flat = new double[3 * vertices.Count];
        for (var v = 0; v < vertices.Count; v++)
        {
            flat[3 * v] = vertices[v].Vector.X;
            flat[(3 * v) + 1] = vertices[v].Vector.Y;
            flat[(3 * v) + 2] = vertices[v].Vector.Z;
        }

        return (flat, triangles.ToArray(), null);
    }

    /// <summary>The mesh's problem at the JSON value it names (a triangle, a vertex), or for an OBJ file at its key.</summary>
    private static SceneException MeshError(ObjectReader reader, ObjectReader mesh, string? obj, ClothMeshException e)
    {
        var problem = char.ToLowerInvariant(e.Message[0]) + e.Message.Substring(1).TrimEnd('.');
        if (obj is not null)
        {
            return mesh.Error(mesh.Get("obj")!.Value, mesh.PathOf("obj"), $"the mesh of {obj} cannot be a cloth: {problem}");
        }

        if (e.Problem == ClothMeshProblem.DuplicateVertex && e.Vertex >= 0)
        {
            problem += "; or give the cloth \"weld\": true";
        }

        var (key, index) = e.Triangle >= 0 ? ("triangles", e.Triangle) : e.Vertex >= 0 ? ("vertices", e.Vertex) : ("triangles", -1);
        var list = mesh.Get(key)!.Value;
        if (index < 0 || index >= list.Count)
        {
            return mesh.Error(list, mesh.PathOf(key), problem, showValue: false);
        }

        return mesh.Error(list.Elements()[index], ObjectReader.Index(mesh.PathOf(key), index), problem);
    }

    private static void ReadStretch(ObjectReader reader, MeshClothBuilder builder)
    {
        builder.MembraneDamping = 0.0;
        if (reader.Object("stretch", "a cloth's stretch") is not { } stretch)
        {
            return;
        }

        if (stretch.Has("stiffness"))
        {
            if (stretch.Has("modulus") || stretch.Has("poisson"))
            {
                throw stretch.ObjectError("give {\"stiffness\": k} (springs on the edges) or {\"modulus\": Y, \"poisson\": nu} (a membrane), not both");
            }

            builder.Stretch = ClothStretch.EdgeSprings;
            builder.SpringStiffness = stretch.Number("stiffness", null, ValueRule.NonNegative, "N/m");
            builder.SpringDamping = stretch.Number("damping", 0.0, ValueRule.NonNegative, "N s/m");
        }
        else
        {
            builder.Stretch = ClothStretch.Membrane;
            builder.Modulus = stretch.Number("modulus", null, ValueRule.Positive, "N/m");
            var poisson = stretch.Number("poisson", 0.3, ValueRule.NonNegative, string.Empty);
            if (!(poisson < 0.5))
            {
                throw stretch.Error(stretch.Get("poisson")!.Value, stretch.PathOf("poisson"), "must be from 0 to less than 0.5");
            }

            builder.Poisson = poisson;
            builder.MembraneDamping = stretch.Number("damping", 0.0, ValueRule.NonNegative, "N s/m");
        }

        stretch.Finish();
    }

    private sealed class ClothObject : SceneObject
    {
        private readonly MeshClothBuilder _builder;
        private readonly Vector3d[] _velocities;
        private readonly double _thickness;
        private readonly bool _aerodynamics;
        private readonly bool _selfCollision;
        private int _first;

        public ClothObject(MeshClothBuilder builder, Vector3d[] velocities, double thickness, bool aerodynamics, bool selfCollision)
        {
            _builder = builder;
            _velocities = velocities;
            _thickness = thickness;
            _aerodynamics = aerodynamics;
            _selfCollision = selfCollision;
        }

        public override int ParticleCount => _builder.Mesh.ParticleCount;

        public override void AddParticles(SceneBuilder builder)
        {
            _first = _builder.AddParticles(builder.World, _velocities);
            if (_thickness > 0)
            {
                for (var i = 0; i < ParticleCount; i++)
                {
                    builder.World.SetRadius(_first + i, _thickness / 2); // the contract: the collision radius is half the thickness
                }
            }
        }

        public override void AddElements(SceneBuilder builder)
        {
            builder.Count("cloth triangles", _builder.Mesh.TriangleCount);
            var springs = _builder.NeedsSprings ? builder.Springs : null;
            var before = springs?.Count ?? 0;
            var membrane = _builder.Stretch == ClothStretch.Membrane ? builder.Membrane : null;
            var bending = _builder.BendingRigidity > 0 ? builder.Bending : null;
            var elements = bending?.Count ?? 0;
            _builder.AddElements(_first, springs, membrane, bending);
            builder.Count("springs", (springs?.Count ?? 0) - before);
            builder.Count("bending elements", (bending?.Count ?? 0) - elements);
            if (_aerodynamics)
            {
                _builder.AddTriangles(_first, builder.Aerodynamics);
                builder.Count("aerodynamic triangles", _builder.Mesh.TriangleCount);
            }

            var triangles = _builder.Mesh.ParticleTriangles.ToArray();
            for (var t = 0; t < _builder.Mesh.TriangleCount; t++)
            {
                builder.AddMeshEdge(_first + triangles[3 * t], _first + triangles[(3 * t) + 1]);
                builder.AddMeshEdge(_first + triangles[(3 * t) + 1], _first + triangles[(3 * t) + 2]);
                builder.AddMeshEdge(_first + triangles[(3 * t) + 2], _first + triangles[3 * t]);
            }

            if (_selfCollision)
            {
                for (var k = 0; k < triangles.Length; k++)
                {
                    triangles[k] += _first;
                }

                builder.AddSelfCollision(triangles, _thickness);
                builder.Count("self-colliding triangles", _builder.Mesh.TriangleCount);
            }
        }
    }
}
