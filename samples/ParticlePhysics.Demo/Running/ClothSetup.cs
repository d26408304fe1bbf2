using System;

namespace ParticlePhysics.Demo.Running;

/// <summary>A cloth's rows: every particle, <c>energy</c>, <c>min_y</c> and <c>max_speed</c>; and its grid, for the snapshot plot.</summary>
internal sealed class ClothSetup : ParticleSetup
{
    public ClothSetup(string name, Func<ParticleWorld> build, int particlesPerSide)
        : base(name, build, particlesPerSide * particlesPerSide, exact: null, meshColumns: true)
    {
        ParticlesPerSide = particlesPerSide;
    }

    /// <summary>n: the cloth has n x n particles, particle (row, col) at index row * n + col.</summary>
    public int ParticlesPerSide { get; }
}
