using System;
using System.Collections.Generic;

namespace ParticlePhysics.Demo.Running;

/// <summary>A cloth's rows: every particle, <c>energy</c>, <c>min_y</c> and <c>max_speed</c>; and its grid, for the snapshot plot.</summary>
internal class ClothSetup : ParticleSetup
{
    public ClothSetup(
        string name,
        Func<ParticleWorld> build,
        int particlesPerSide,
        IReadOnlyList<ExtraColumn>? extras = null,
        Func<IStepObserver>? observer = null)
        : base(name, build, particlesPerSide * particlesPerSide, exact: null, meshColumns: true, extras, observer)
    {
        ParticlesPerSide = particlesPerSide;
    }

    /// <summary>n: the cloth has n x n particles, particle (row, col) at index row * n + col.</summary>
    public int ParticlesPerSide { get; }

    /// <inheritdoc />
    public override int SurfaceSide => ParticlesPerSide;
}
