using System;
using System.Collections.Generic;
using System.IO;
using ParticlePhysics.Contacts;
using ParticlePhysics.Scenes.Json;
using ParticlePhysics.Scenes.Kinds;
using ParticlePhysics.Scenes.Meshes;

namespace ParticlePhysics.Scenes.Colliders;

/// <summary>
/// <c>mesh</c> {"mesh", "position", "rotation", "twoSided"}: a triangle mesh collider (<see cref="MeshObstacle"/>).
/// <c>mesh</c> is inline {"vertices": [[x, y, z], ...], "triangles": [[a, b, c], ...]} or {"obj": "file.obj"} (relative
/// to the scene's folder); <c>position</c> ([0, 0, 0]) and <c>rotation</c> (a unit quaternion [w, x, y, z]) place it;
/// <c>twoSided</c> (false: the back of the surface is solid, and a closed mesh has an inside).
/// </summary>
internal sealed class MeshKind : ColliderKind
{
    public override string Name => "mesh";

    protected override Func<double, double, Obstacle> ReadShape(ObjectReader reader, SceneReadContext context)
    {
        var source = reader.Object("mesh", "mesh") ?? throw reader.ObjectError("mesh needs \"mesh\": {\"vertices\", \"triangles\"} or {\"obj\": \"file.obj\"}");
        var mesh = ReadMesh(source, context);
        source.Finish();
        var position = reader.Vector("position", Vector3d.Zero, "m");
        var rotation = BoxKind.ReadRotation(reader, "rotation");
        var twoSided = reader.Boolean("twoSided", false);
        return (e, mu) =>
        {
            var obstacle = new MeshObstacle(mesh.Vertices, mesh.Triangles, twoSided, e, mu) { Position = position };
            if (rotation is { } q)
            {
                obstacle.SetOrientation(q.Rotate(new Vector3d(1, 0, 0)), q.Rotate(new Vector3d(0, 1, 0)));
            }

            return obstacle;
        };
    }

    /// <summary>The mesh of a <c>mesh</c> key, inline or from an OBJ file.</summary>
    internal static Meshes.TriangleMesh ReadMesh(ObjectReader source, SceneReadContext context)
    {
        if (source.String("obj") is { } file)
        {
            if (source.Has("vertices") || source.Has("triangles"))
            {
                throw source.ObjectError("takes \"obj\" or \"vertices\" and \"triangles\", not both");
            }

            return ObjReader.Read(Path.Combine(context.Directory, file), file);
        }

        var vertices = source.Vectors("vertices", "m") ?? throw source.ObjectError("mesh needs \"vertices\" [[x, y, z], ...] and \"triangles\" [[a, b, c], ...], or \"obj\"");
        var corners = source.Get("triangles") ?? throw source.ObjectError("mesh needs \"triangles\" [[a, b, c], ...]: three vertex indices each");
        var path = source.PathOf("triangles");
        if (corners.Kind != JsonKind.Array || corners.Count == 0)
        {
            throw source.Error(corners, path, "must be a list of triangles [a, b, c] of vertex indices");
        }

        var triangles = new List<int>(3 * corners.Count);
        var t = 0;
        foreach (var triangle in corners.Elements())
        {
            var at = ObjectReader.Index(path, t++);
            if (triangle.Kind != JsonKind.Array || triangle.Count != 3)
            {
                throw source.Error(triangle, at, "must be a triangle [a, b, c] of vertex indices");
            }

            foreach (var corner in triangle.Elements())
            {
                if (!corner.IsNumber || corner.Number < 0 || corner.Number >= vertices.Count || corner.Number != Math.Floor(corner.Number))
                {
                    throw source.Error(corner, at, FormattableString.Invariant($"must hold vertex indices from 0 to {vertices.Count - 1}"));
                }

                triangles.Add((int)corner.Number);
            }
        }

        var xyz = new double[3 * vertices.Count];
        for (var i = 0; i < vertices.Count; i++)
        {
            (xyz[3 * i], xyz[(3 * i) + 1], xyz[(3 * i) + 2]) = (vertices[i].Vector.X, vertices[i].Vector.Y, vertices[i].Vector.Z);
        }

        return new Meshes.TriangleMesh(xyz, triangles.ToArray());
    }
}
