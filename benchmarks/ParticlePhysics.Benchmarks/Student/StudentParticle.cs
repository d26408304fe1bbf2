using System.Numerics;

namespace ParticlePhysics.Benchmarks.Student;

/// <summary>
/// A particle the way a course student writes it: a class with System.Numerics vectors (single precision, as in
/// Unity), its own force accumulator and a pinned flag. The baseline of the comparison, not library code.
/// </summary>
public class StudentParticle
{
    public StudentParticle(Vector3 position, float mass)
    {
        Position = position;
        Mass = mass;
    }

    public Vector3 Position { get; set; }

    public Vector3 Velocity { get; set; }

    public Vector3 Force { get; set; }

    public float Mass { get; set; }

    public bool IsPinned { get; set; }
}
