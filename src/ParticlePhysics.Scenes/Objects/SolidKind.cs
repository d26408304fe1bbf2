using System;
using ParticlePhysics.Bodies;
using ParticlePhysics.Constraints;
using ParticlePhysics.Scenes.Colliders;
using ParticlePhysics.Scenes.Kinds;

namespace ParticlePhysics.Scenes.Objects;

/// <summary>
/// <c>rigid</c> and <c>soft</c>: a body of particles held in shape by shape matching (<see cref="ShapeMatching"/>).
/// Its shape is <c>box</c> {"center", "size", "rotation"} or <c>mesh</c> (a closed mesh, inline or {"obj"}, filled in
/// its own frame, then placed by <c>position</c> and <c>rotation</c> as a mesh collider is), filled at <c>spacing</c> h
/// by <see cref="BodyLattice"/> (particles of radius h / 2, in lattice order, x fastest).
/// <c>mass</c> (total, kg, default 1) or <c>density</c> (kg/m^3, times the shape's volume), shared equally;
/// <c>velocity</c> and <c>angularVelocity</c> (rad/s about the centre of mass, world axes), default rest;
/// <c>friction</c> and <c>restitution</c> of its own (met with the other side's by their mean). <c>soft</c> adds
/// <c>stiffness</c> (0..1], default 0.5, and <c>plasticity</c> {"yield" (m), "creep" ((0, 1], default 0.5)}. Its particles never collide with each other, and collide with every other
/// particle of a radius and every collider.
/// </summary>
internal sealed class SolidKind : ISceneObjectKind
{
    private readonly bool _soft;

    private SolidKind(string name, bool soft)
    {
        Name = name;
        _soft = soft;
    }

    public static SolidKind Rigid { get; } = new("rigid", soft: false);

    public static SolidKind Soft { get; } = new("soft", soft: true);

    public string Name { get; }

    public SceneObject Read(ObjectReader reader, SceneReadContext context)
    {
        var spacing = reader.Number("spacing", null, ValueRule.Positive, "m");
        var (positions, rotation, volume) = ReadShape(reader, context, spacing);
        if (reader.Has("mass") && reader.Has("density"))
        {
            throw reader.Error(reader.Get("density")!.Value, reader.PathOf("density"), "give \"mass\" (kg, the body's total) or \"density\" (kg/m^3), not both", showValue: false);
        }

        if (!_soft && OnOneLine(positions))
        {
            throw reader.ObjectError(FormattableString.Invariant($"fills with {positions.Length} particles on one line at spacing {spacing:G6} m; a rigid body's spin about that line would be undefined: give a smaller spacing"));
        }

        var mass = reader.Has("density") ? reader.Number("density", null, ValueRule.Positive, "kg/m^3") * volume : reader.Number("mass", 1.0, ValueRule.Mass, "kg");
        var each = mass / positions.Length;
        if (!(each > 0) || double.IsInfinity(each) || double.IsInfinity(1.0 / each))
        {
            throw reader.ObjectError(FormattableString.Invariant($"its mass {mass:G6} kg shared by its {positions.Length} particles leaves each one whose inverse is not finite"));
        }

        return new SolidObject(_soft, positions, rotation, spacing / 2, each)
        {
            Velocity = reader.Vector("velocity", Vector3d.Zero, "m/s"),
            AngularVelocity = reader.Vector("angularVelocity", Vector3d.Zero, "rad/s"),
            Friction = reader.Has("friction") ? reader.Number("friction", null, ValueRule.NonNegative, string.Empty) : double.NaN,
            Restitution = reader.Has("restitution") ? reader.Number("restitution", null, ValueRule.Fraction, string.Empty) : double.NaN,
            Stiffness = _soft ? StiffnessOf(reader) : 1.0,
            Plasticity = _soft ? PlasticityOf(reader) : null,
        };
    }

    // "plasticity": {"yield" (m, required), "creep" ((0, 1], default 0.5)}.
    private static (double Yield, double Creep)? PlasticityOf(ObjectReader reader)
    {
        var plasticity = reader.Object("plasticity", "a soft body's plasticity");
        if (plasticity is null)
        {
            return null;
        }

        var yield = plasticity.Number("yield", null, ValueRule.Positive, "m");
        var creep = plasticity.Number("creep", 0.5, ValueRule.Positive, string.Empty);
        if (creep > 1.0)
        {
            throw plasticity.Error(plasticity.Get("creep")!.Value, plasticity.PathOf("creep"), "must be in (0, 1]: the fraction of what passes the yield taken into the rest shape at each projection");
        }

        plasticity.Finish();
        return (yield, creep);
    }

    private static bool OnOneLine(Vector3d[] positions)
    {
        var far = positions[0];
        foreach (var p in positions)
        {
            far = (p - positions[0]).LengthSquared > (far - positions[0]).LengthSquared ? p : far;
        }

        var axis = far - positions[0];
        foreach (var p in positions)
        {
            if (Vector3d.Cross(p - positions[0], axis).Length > 1e-9 * axis.LengthSquared)
            {
                return false;
            }
        }

        return positions.Length > 1;
    }

    private static double StiffnessOf(ObjectReader reader)
    {
        var stiffness = reader.Number("stiffness", 0.5, ValueRule.Positive, string.Empty);
        if (stiffness > 1.0)
        {
            throw reader.Error(reader.Get("stiffness")!.Value, reader.PathOf("stiffness"), "must be in (0, 1]: the fraction of the way to its shape a soft body moves at each projection");
        }

        return stiffness;
    }

    // The particles of a box or a closed mesh, the body's frame, and the shape's volume (for a density).
    private (Vector3d[] Positions, Rotation3d Rotation, double Volume) ReadShape(ObjectReader reader, SceneReadContext context, double spacing)
    {
        var box = reader.Object("box", "a body's box");
        var meshSource = reader.Object("mesh", "a body's mesh");
        if ((box is null) == (meshSource is null))
        {
            throw reader.ObjectError($"a {Name} object needs \"box\": {{\"center\", \"size\", \"rotation\"}} or \"mesh\": {{\"vertices\", \"triangles\"}} or {{\"obj\"}} (a closed mesh), one of them");
        }

        try
        {
            if (box is not null)
            {
                var center = box.Vector("center", null, "m");
                var size = box.Vector("size", null, "m");
                if (!(size.X > 0 && size.Y > 0 && size.Z > 0))
                {
                    throw box.Error(box.Get("size")!.Value, box.PathOf("size"), "must be three positive numbers (m): the box's sides along its own axes");
                }

                var rotation = BoxKind.ReadRotation(box, "rotation") ?? Rotation3d.Identity;
                box.Finish();
                return (CheckCount(reader, BodyLattice.Box(center, size, rotation, spacing)), rotation, size.X * size.Y * size.Z);
            }

            var mesh = MeshKind.ReadMesh(meshSource!, context);
            meshSource!.Finish();
            var vertices = new Vector3d[mesh.VertexCount];
            for (var i = 0; i < vertices.Length; i++)
            {
                vertices[i] = mesh.Vertex(i);
            }

            // Filled in the mesh's own frame, so that the lattice turns with it, then placed as a mesh collider is.
            var volume = BodyLattice.MeshVolume(vertices, mesh.Triangles);
            var position = reader.Vector("position", Vector3d.Zero, "m");
            var turn = BoxKind.ReadRotation(reader, "rotation") ?? Rotation3d.Identity;
            var particles = CheckCount(reader, BodyLattice.Mesh(vertices, mesh.Triangles, spacing));
            for (var k = 0; k < particles.Length; k++)
            {
                particles[k] = position + turn.Rotate(particles[k]);
            }

            return (particles, turn, volume);
        }
        catch (ArgumentException e)
        {
            var key = box is not null ? "box" : "mesh";
            var message = e.Message.Split('\n')[0];
            var parameter = message.IndexOf(" (Parameter", StringComparison.Ordinal);
            throw reader.Error(reader.Get(key)!.Value, reader.PathOf(key), "cannot be filled: " + (parameter >= 0 ? message.Substring(0, parameter) : message), showValue: false);
        }
    }

    private static Vector3d[] CheckCount(ObjectReader reader, Vector3d[] positions)
    {
        if (positions.Length > ParticleWorld.MaxParticles)
        {
            throw reader.ObjectError(FormattableString.Invariant($"fills with {positions.Length:N0} particles; a scene holds at most {ParticleWorld.MaxParticles:N0}"));
        }

        return positions;
    }

    private sealed class SolidObject : SceneObject
    {
        private readonly bool _soft;
        private readonly Vector3d[] _positions;
        private readonly Rotation3d _rotation;
        private readonly double _radius;
        private readonly double _mass;
        private int _first;

        public SolidObject(bool soft, Vector3d[] positions, Rotation3d rotation, double radius, double mass)
        {
            _soft = soft;
            _positions = positions;
            _rotation = rotation;
            _radius = radius;
            _mass = mass;
        }

        public Vector3d Velocity { get; set; }

        public Vector3d AngularVelocity { get; set; }

        public double Friction { get; set; }

        public double Restitution { get; set; }

        public double Stiffness { get; set; }

        public (double Yield, double Creep)? Plasticity { get; set; }

        public override int ParticleCount => _positions.Length;

        public override void AddParticles(SceneBuilder builder) => _first = builder.AddSpheres(_positions, _mass, _radius);

        public override void AddElements(SceneBuilder builder)
        {
            var particles = new int[_positions.Length];
            for (var k = 0; k < particles.Length; k++)
            {
                particles[k] = _first + k;
            }

            var bodies = builder.Bodies;
            var body = _soft ? bodies.AddSoft(particles, Stiffness, _rotation) : bodies.AddRigid(particles, _rotation);
            if (Plasticity is { } plasticity)
            {
                bodies.SetPlasticity(body, plasticity.Yield, plasticity.Creep);
            }

            if (Velocity != Vector3d.Zero || AngularVelocity != Vector3d.Zero)
            {
                bodies.SetMotion(body, Velocity, AngularVelocity);
            }

            builder.AddSolid(_first, particles.Length, Friction, Restitution);
            builder.Count(_soft ? "soft bodies" : "rigid bodies", 1);
        }
    }
}
