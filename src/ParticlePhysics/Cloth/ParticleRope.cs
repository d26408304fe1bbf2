using ParticlePhysics.Constraints;
using ParticlePhysics.Forces;

namespace ParticlePhysics.Cloth;

/// <summary>A rope built by <see cref="RopeBuilder"/>: where its particles are, and the forces and constraints that move it.</summary>
public sealed class ParticleRope
{
    internal ParticleRope(
        ParticleWorld world,
        int firstParticle,
        int count,
        SpringNetwork? springs,
        SpringProjection? springProjection,
        RodNetwork? rods,
        QuadraticBending? bending,
        BendingProjection? bendingProjection,
        LinearDrag drag,
        Gravity? gravity)
    {
        System = world;
        FirstParticle = firstParticle;
        ParticleCount = count;
        Springs = springs;
        SpringProjection = springProjection;
        Rods = rods;
        Bending = bending;
        BendingProjection = bendingProjection;
        Drag = drag;
        Gravity = gravity;
    }

    /// <summary>The world that holds the rope.</summary>
    public ParticleWorld System { get; }

    /// <summary>The world's index of point 0; point i is FirstParticle + i.</summary>
    public int FirstParticle { get; }

    /// <summary>The number of points.</summary>
    public int ParticleCount { get; }

    /// <summary>The segments' springs, or null for an inextensible rope.</summary>
    public SpringNetwork? Springs { get; }

    /// <summary>The springs as xpbd constraints, or null.</summary>
    public SpringProjection? SpringProjection { get; }

    /// <summary>The segments' rods (an inextensible rope), or null.</summary>
    public RodNetwork? Rods { get; }

    /// <summary>The bending, or null.</summary>
    public QuadraticBending? Bending { get; }

    /// <summary>The bending as xpbd constraints, or null.</summary>
    public BendingProjection? BendingProjection { get; }

    /// <summary>The linear drag on the rope's particles.</summary>
    public LinearDrag Drag { get; }

    /// <summary>The gravity <see cref="RopeBuilder.Build"/> added, or null.</summary>
    public Gravity? Gravity { get; }
}
