using System;
using System.Collections.Generic;

namespace ParticlePhysics.Scenes;

/// <summary>
/// Constant forces on chosen particles, the scene's <c>load</c>: F_i = F, whatever the state. Its Jacobian is zero,
/// so implicit Euler takes it at its value, which is exact for a constant force.
/// </summary>
public sealed class ConstantLoads : IForceGenerator, IForceJacobian
{
    private readonly ParticleWorld _world;
    private readonly List<int> _particles = new();
    private readonly List<Vector3d> _forces = new();

    /// <summary>No loads yet, for the particles of <paramref name="world"/>.</summary>
    public ConstantLoads(ParticleWorld world)
    {
        _world = world ?? throw new ArgumentNullException(nameof(world));
    }

    /// <summary>The number of loads.</summary>
    public int Count => _particles.Count;

    /// <summary>Adds the force <paramref name="force"/> (N, finite) on particle <paramref name="particle"/>.</summary>
    public void Add(int particle, Vector3d force)
    {
        if ((uint)particle >= (uint)_world.Count)
        {
            throw new ArgumentOutOfRangeException(nameof(particle), particle, $"particle must be 0 to {_world.Count - 1}.");
        }

        if (!force.IsFinite)
        {
            throw new ArgumentOutOfRangeException(nameof(force), force, "force must be finite.");
        }

        _particles.Add(particle);
        _forces.Add(force);
    }

    /// <summary>The particle and the force of load <paramref name="load"/> (what a renderer draws).</summary>
    public (int Particle, Vector3d Force) Get(int load) => (_particles[load], _forces[load]);

    /// <inheritdoc />
    public void AddForces(in ParticleState state, Span<double> forces)
    {
        for (var k = 0; k < _particles.Count; k++)
        {
            var o = 3 * _particles[k];
            var f = _forces[k];
            forces[o] += f.X;
            forces[o + 1] += f.Y;
            forces[o + 2] += f.Z;
        }
    }

    /// <inheritdoc />
    public void Linearize(in ParticleState state, double positionScale, double velocityScale, Span<double> positionJacobianTimesVelocity)
    {
    }

    /// <inheritdoc />
    public void AddJacobianProduct(ReadOnlySpan<double> w, Span<double> result)
    {
    }

    /// <inheritdoc />
    public void AddDiagonalBlocks(Span<double> blocks)
    {
    }
}
