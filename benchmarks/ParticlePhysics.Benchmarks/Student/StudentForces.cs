using System.Numerics;

namespace ParticlePhysics.Benchmarks.Student;

/// <summary>A force acting on one particle at a time: the student's world calls it once per particle (a virtual call each).</summary>
public abstract class StudentForce
{
    public abstract void ApplyTo(StudentParticle particle);
}

/// <summary>Gravity m g, g = (0, -g, 0).</summary>
public class StudentGravity : StudentForce
{
    public StudentGravity(float g)
    {
        Acceleration = new Vector3(0, -g, 0);
    }

    public Vector3 Acceleration { get; }

    public override void ApplyTo(StudentParticle particle)
    {
        particle.Force += particle.Mass * Acceleration;
    }
}

/// <summary>Linear drag -lambda v.</summary>
public class StudentDrag : StudentForce
{
    public StudentDrag(float lambda)
    {
        Lambda = lambda;
    }

    public float Lambda { get; }

    public override void ApplyTo(StudentParticle particle)
    {
        particle.Force -= Lambda * particle.Velocity;
    }
}

/// <summary>
/// A damped spring between two particle objects, with a virtual Apply so that other kinds of springs can derive
/// from it: F_a = -(k (l - L) + c (v_a - v_b) . u) u, F_b = -F_a, zero when l = 0 (the contract's formula).
/// </summary>
public class StudentSpring
{
    public StudentSpring(StudentParticle a, StudentParticle b, float stiffness, float restLength, float damping)
    {
        A = a;
        B = b;
        Stiffness = stiffness;
        RestLength = restLength;
        Damping = damping;
    }

    public StudentParticle A { get; }

    public StudentParticle B { get; }

    public float Stiffness { get; }

    public float RestLength { get; }

    public float Damping { get; }

    public virtual void Apply()
    {
        var d = A.Position - B.Position;
        var length = d.Length();
        if (length == 0)
        {
            return;
        }

        var u = d / length;
        var closing = Vector3.Dot(A.Velocity - B.Velocity, u);
        var force = -((Stiffness * (length - RestLength)) + (Damping * closing)) * u;
        A.Force += force;
        B.Force -= force;
    }
}
