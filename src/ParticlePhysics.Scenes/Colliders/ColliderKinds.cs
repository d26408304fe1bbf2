using System;
using ParticlePhysics.Constraints;
using ParticlePhysics.Contacts;
using ParticlePhysics.Scenes.Kinds;

namespace ParticlePhysics.Scenes.Colliders;

/// <summary>
/// What every collider has: <c>restitution</c> (0 to 1, default 0), <c>friction</c> (&gt;= 0, default 0) and
/// <c>velocity</c> ([0, 0, 0] m/s: it moves at that constant velocity). A collider kind reads its shape, and this the rest.
/// </summary>
internal abstract class ColliderKind : IColliderKind
{
    public abstract string Name { get; }

    public SceneCollider Read(ObjectReader reader, SceneReadContext context)
    {
        var shape = ReadShape(reader, context);
        var restitution = reader.Number("restitution", 0.0, ValueRule.Fraction, string.Empty);
        var friction = reader.Number("friction", 0.0, ValueRule.NonNegative, string.Empty);
        var velocity = reader.Vector("velocity", Vector3d.Zero, "m/s");
        var collider = new Collider(Name, () =>
        {
            var obstacle = shape(restitution, friction);
            obstacle.Velocity = velocity;
            return obstacle;
        });
        try
        {
            collider.CreateObstacle(); // the core's own checks, with the object's path
        }
        catch (ArgumentException e)
        {
            throw reader.ObjectError(e.Message.Split('\n')[0].Split(new[] { " (Parameter" }, StringSplitOptions.None)[0]);
        }

        return collider;
    }

    /// <summary>Reads the shape's keys (files named relative to the scene's folder); returns how to make the obstacle from its restitution and friction.</summary>
    protected abstract Func<double, double, Obstacle> ReadShape(ObjectReader reader, SceneReadContext context);

    private sealed class Collider : SceneCollider
    {
        private readonly Func<Obstacle> _create;

        public Collider(string kind, Func<Obstacle> create)
        {
            Kind = kind;
            _create = create;
        }

        public override string Kind { get; }

        public override Obstacle CreateObstacle() => _create();
    }
}

/// <summary><c>plane</c> {"point", "normal"}: the half-space on the side the normal points to is free.</summary>
internal sealed class PlaneKind : ColliderKind
{
    public override string Name => "plane";

    protected override Func<double, double, Obstacle> ReadShape(ObjectReader reader, SceneReadContext context)
    {
        var point = reader.Vector("point", null, "m");
        var normal = reader.Vector("normal", null, "any length but 0");
        if (normal == Vector3d.Zero)
        {
            throw reader.Error(reader.Get("normal")!.Value, reader.PathOf("normal"), "must not be [0, 0, 0]: it says which side is free");
        }

        return (e, mu) => new PlaneObstacle(point, normal, e, mu);
    }
}

/// <summary><c>sphere</c> {"center", "radius"}.</summary>
internal sealed class SphereKind : ColliderKind
{
    public override string Name => "sphere";

    protected override Func<double, double, Obstacle> ReadShape(ObjectReader reader, SceneReadContext context)
    {
        var center = reader.Vector("center", null, "m");
        var radius = reader.Number("radius", null, ValueRule.Positive, "m");
        return (e, mu) => new SphereObstacle(center, radius, e, mu);
    }
}

/// <summary><c>capsule</c> {"a", "b", "radius"}: the points within radius of the segment from a to b.</summary>
internal sealed class CapsuleKind : ColliderKind
{
    public override string Name => "capsule";

    protected override Func<double, double, Obstacle> ReadShape(ObjectReader reader, SceneReadContext context)
    {
        var a = reader.Vector("a", null, "m");
        var b = reader.Vector("b", null, "m");
        var radius = reader.Number("radius", null, ValueRule.Positive, "m");
        return (e, mu) => new CapsuleObstacle(a, b, radius, e, mu);
    }
}

/// <summary>
/// <c>box</c> {"center", "halfExtents", "rotation"}: a solid box turned by the unit quaternion [w, x, y, z]
/// (default [1, 0, 0, 0], no turn; within 1e-3 of unit length, then normalised).
/// </summary>
internal sealed class BoxKind : ColliderKind
{
    public override string Name => "box";

    protected override Func<double, double, Obstacle> ReadShape(ObjectReader reader, SceneReadContext context)
    {
        var center = reader.Vector("center", null, "m");
        var half = reader.Vector("halfExtents", null, "m");
        var halfAt = reader.Get("halfExtents")!.Value;
        if (!(half.X > 0 && half.Y > 0 && half.Z > 0))
        {
            throw reader.Error(halfAt, reader.PathOf("halfExtents"), "must be three positive numbers (m): half the box's size along its axes");
        }

        var rotation = ReadRotation(reader, "rotation");
        return (e, mu) =>
        {
            var box = new BoxObstacle(center, half, e, mu);
            if (rotation is { } q)
            {
                box.SetOrientation(q.Rotate(new Vector3d(1, 0, 0)), q.Rotate(new Vector3d(0, 1, 0)));
            }

            return box;
        };
    }

    /// <summary>A unit quaternion [w, x, y, z], or null when absent or [1, 0, 0, 0].</summary>
    internal static Rotation3d? ReadRotation(ObjectReader reader, string key)
    {
        if (reader.Get(key) is not { } value)
        {
            return null;
        }

        var path = reader.PathOf(key);
        if (value.Kind != Json.JsonKind.Array || value.Count != 4)
        {
            throw reader.Error(value, path, "must be a unit quaternion [w, x, y, z]");
        }

        var q = value.Elements().ConvertAll(v => reader.CheckNumber(v, path, ValueRule.Finite, string.Empty));
        var norm = Math.Sqrt((q[0] * q[0]) + (q[1] * q[1]) + (q[2] * q[2]) + (q[3] * q[3]));
        if (!(Math.Abs(norm - 1.0) <= 1e-3))
        {
            throw reader.Error(value, path, FormattableString.Invariant($"must be a unit quaternion [w, x, y, z]; its length is {norm:G6}, not 1 (to 1e-3)"));
        }

        return q[0] == 1.0 && q[1] == 0.0 && q[2] == 0.0 && q[3] == 0.0 ? null : new Rotation3d(q[1], q[2], q[3], q[0]);
    }
}
