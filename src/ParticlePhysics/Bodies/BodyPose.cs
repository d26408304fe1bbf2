using ParticlePhysics.Constraints;

namespace ParticlePhysics.Bodies;

/// <summary>
/// Where a body of <see cref="ShapeMatching"/> is and how it moves, for rendering a mesh on it: a point p of the body's
/// own frame is at <c>Position + Rotation.Rotate(p)</c> in the world.
/// </summary>
public readonly struct BodyPose
{
    /// <summary>A pose.</summary>
    public BodyPose(Vector3d position, Rotation3d rotation, Vector3d linearVelocity, Vector3d angularVelocity)
    {
        Position = position;
        Rotation = rotation;
        LinearVelocity = linearVelocity;
        AngularVelocity = angularVelocity;
    }

    /// <summary>The centre of mass, m: the origin of the body's frame.</summary>
    public Vector3d Position { get; }

    /// <summary>The rotation from the body's frame to the world.</summary>
    public Rotation3d Rotation { get; }

    /// <summary>The velocity of the centre of mass, m/s.</summary>
    public Vector3d LinearVelocity { get; }

    /// <summary>
    /// The angular velocity, rad/s, in the world's axes: I^-1 L, from the particles' angular momentum L about the
    /// centre of mass and the inertia I of the rest shape turned by <see cref="Rotation"/>.
    /// </summary>
    public Vector3d AngularVelocity { get; }
}
