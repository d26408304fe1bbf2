using System;
using ParticlePhysics.Contacts;
using ParticlePhysics.Scenes.Json;
using ParticlePhysics.Scenes.Kinds;

namespace ParticlePhysics.Scenes.Colliders;

/// <summary>
/// <c>heightfield</c> {"origin", "cellSize", "heights"}: a terrain (<see cref="HeightFieldObstacle"/>). Row r of
/// <c>heights</c> lies at z = origin.z + r dz, column c at x = origin.x + c dx, at height origin.y + heights[r][c]; each
/// cell is two triangles.
/// </summary>
internal sealed class HeightFieldKind : ColliderKind
{
    public override string Name => "heightfield";

    protected override Func<double, double, Obstacle> ReadShape(ObjectReader reader, SceneReadContext context)
    {
        var origin = reader.Vector("origin", Vector3d.Zero, "m");
        var cell = reader.Numbers("cellSize", ValueRule.Positive, "m") ?? throw reader.ObjectError("heightfield needs \"cellSize\": [dx, dz], two positive numbers (m)");
        if (cell.Count != 2)
        {
            throw reader.Error(reader.Get("cellSize")!.Value, reader.PathOf("cellSize"), "must be [dx, dz], two positive numbers (m)");
        }

        var rows = reader.Get("heights") ?? throw reader.ObjectError("heightfield needs \"heights\": [[...], ...], a row of heights (m) per z, at least 2 by 2");
        var path = reader.PathOf("heights");
        if (rows.Kind != JsonKind.Array || rows.Count < 2)
        {
            throw reader.Error(rows, path, "must be at least 2 rows [[h, ...], ...] of heights (m)");
        }

        var list = rows.Elements();
        var columns = list[0].Kind == JsonKind.Array ? list[0].Count : 0;
        var heights = new double[list.Count, Math.Max(columns, 2)];
        for (var r = 0; r < list.Count; r++)
        {
            var at = ObjectReader.Index(path, r);
            if (list[r].Kind != JsonKind.Array || list[r].Count != columns || columns < 2)
            {
                throw reader.Error(list[r], at, FormattableString.Invariant($"must be a row of {Math.Max(columns, 2)} heights (m), as long as the first, at least 2"));
            }

            var c = 0;
            foreach (var h in list[r].Elements())
            {
                heights[r, c] = reader.CheckNumber(h, ObjectReader.Index(at, c), ValueRule.Finite, "m");
                c++;
            }
        }

        return (e, mu) => new HeightFieldObstacle(origin, cell[0], cell[1], heights, e, mu);
    }
}
