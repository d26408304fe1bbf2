using System;
using System.Collections.Generic;
using System.Numerics;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Benchmarks.Student;

/// <summary>
/// The course's cloth as a student writes it: a list of particle objects, a list of force objects called once per
/// particle each (a virtual call per particle per force), a list of spring objects (a virtual call per spring), a new
/// vector per operation, and RK4 done naively: the state and each stage's slopes copied into new lists at every step.
/// Same topology, defaults and formulas as <see cref="ClothScenario"/>; the verify mode checks that both give nearly
/// the same cloth. It is the baseline the library must beat, kept inside the benchmark project only.
/// </summary>
public class StudentCloth
{
    private readonly List<Vector3> _initialPositions = new();

    public StudentCloth(int n)
    {
        var scenario = new ClothScenario { Resolution = 1.0 / (n - 1) };
        var r = (float)scenario.Resolution;
        var k = (float)scenario.Stiffness;
        var c = (float)scenario.Damping;
        var mass = (float)(scenario.Mass / (n * n));
        for (var row = 0; row < n; row++)
        {
            for (var col = 0; col < n; col++)
            {
                Particles.Add(new StudentParticle(new Vector3(col * r, 0, row * r), mass));
            }
        }

        Particles[0].IsPinned = true;
        Particles[n - 1].IsPinned = true;
        for (var row = 0; row < n; row++)
        {
            for (var col = 0; col < n; col++)
            {
                var i = (row * n) + col;
                if (col + 1 < n)
                {
                    AddSpring(i, i + 1, k, r, c);
                }

                if (row + 1 < n)
                {
                    AddSpring(i, i + n, k, r, c);
                }

                if (row + 1 < n && col + 1 < n)
                {
                    AddSpring(i, i + n + 1, k, r * MathF.Sqrt(2), c);
                    AddSpring(i + 1, i + n, k, r * MathF.Sqrt(2), c);
                }

                if (col + 2 < n)
                {
                    AddSpring(i, i + 2, k, 2 * r, c);
                }

                if (row + 2 < n)
                {
                    AddSpring(i, i + (2 * n), k, 2 * r, c);
                }
            }
        }

        Forces.Add(new StudentGravity((float)scenario.Gravity));
        Forces.Add(new StudentDrag((float)scenario.Drag));
        foreach (var p in Particles)
        {
            _initialPositions.Add(p.Position);
        }
    }

    public List<StudentParticle> Particles { get; } = new();

    public List<StudentForce> Forces { get; } = new();

    public List<StudentSpring> Springs { get; } = new();

    /// <summary>Puts every particle back at its initial position, at rest.</summary>
    public void Reset()
    {
        for (var i = 0; i < Particles.Count; i++)
        {
            Particles[i].Position = _initialPositions[i];
            Particles[i].Velocity = Vector3.Zero;
        }
    }

    public void ComputeForces()
    {
        foreach (var p in Particles)
        {
            p.Force = Vector3.Zero;
        }

        foreach (var force in Forces)
        {
            foreach (var p in Particles)
            {
                force.ApplyTo(p);
            }
        }

        foreach (var spring in Springs)
        {
            spring.Apply();
        }
    }

    /// <summary>One classical RK4 step, written the straightforward way.</summary>
    public void StepRk4(float dt)
    {
        var x0 = new List<Vector3>();
        var v0 = new List<Vector3>();
        foreach (var p in Particles)
        {
            x0.Add(p.Position);
            v0.Add(p.Velocity);
        }

        var (k1x, k1v) = Slopes();
        MoveTo(x0, v0, k1x, k1v, dt / 2);
        var (k2x, k2v) = Slopes();
        MoveTo(x0, v0, k2x, k2v, dt / 2);
        var (k3x, k3v) = Slopes();
        MoveTo(x0, v0, k3x, k3v, dt);
        var (k4x, k4v) = Slopes();
        for (var i = 0; i < Particles.Count; i++)
        {
            var p = Particles[i];
            if (p.IsPinned)
            {
                continue;
            }

            p.Position = x0[i] + (dt / 6 * (k1x[i] + (2 * k2x[i]) + (2 * k3x[i]) + k4x[i]));
            p.Velocity = v0[i] + (dt / 6 * (k1v[i] + (2 * k2v[i]) + (2 * k3v[i]) + k4v[i]));
        }
    }

    private void AddSpring(int a, int b, float k, float restLength, float c) =>
        Springs.Add(new StudentSpring(Particles[a], Particles[b], k, restLength, c));

    private (List<Vector3> Velocities, List<Vector3> Accelerations) Slopes()
    {
        ComputeForces();
        var velocities = new List<Vector3>();
        var accelerations = new List<Vector3>();
        foreach (var p in Particles)
        {
            velocities.Add(p.IsPinned ? Vector3.Zero : p.Velocity);
            accelerations.Add(p.IsPinned ? Vector3.Zero : p.Force / p.Mass);
        }

        return (velocities, accelerations);
    }

    private void MoveTo(List<Vector3> x0, List<Vector3> v0, List<Vector3> kx, List<Vector3> kv, float h)
    {
        for (var i = 0; i < Particles.Count; i++)
        {
            var p = Particles[i];
            if (p.IsPinned)
            {
                continue;
            }

            p.Position = x0[i] + (h * kx[i]);
            p.Velocity = v0[i] + (h * kv[i]);
        }
    }
}
