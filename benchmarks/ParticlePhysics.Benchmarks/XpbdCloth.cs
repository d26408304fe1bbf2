using System;
using ParticlePhysics.Integrators;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The game case of issue 13: the n x n cloth (<see cref="ClothFixture"/>) stepped by xpbd at one 60 Hz frame per step
/// with <see cref="Substeps"/> substeps, one simulated second (<see cref="StepsPerSecond"/> frames) from rest at a time,
/// as the C reference (<c>reference-c/cloth_xpbd.c</c>) runs it. <see cref="Checksum"/> is the sum of the state, the
/// figure the C program prints after the same second.
/// </summary>
internal sealed class XpbdCloth
{
    /// <summary>Frames per simulated second: 60, so dt = 1/60 s.</summary>
    public const int StepsPerSecond = 60;

    /// <summary>The frame, 1/60 s.</summary>
    public const double FrameTime = 1.0 / StepsPerSecond;

    /// <summary>Substeps per frame: xpbd's default, 10.</summary>
    public const int Substeps = Xpbd.DefaultSubsteps;

    private readonly ClothFixture _cloth;

    public XpbdCloth(int particlesPerSide)
        : this(new ClothFixture(particlesPerSide))
    {
    }

    /// <summary>The cloth with springs of axial damping <paramref name="damping"/> (N s/m).</summary>
    public XpbdCloth(int particlesPerSide, double damping)
        : this(new ClothFixture(particlesPerSide, damping))
    {
    }

    private XpbdCloth(ClothFixture cloth)
    {
        _cloth = cloth;
        Integrator = new Xpbd(Substeps);
    }

    public Xpbd Integrator { get; }

    public ParticleWorld System => _cloth.System;

    public int ParticlesPerSide => _cloth.ParticlesPerSide;

    public int SpringCount => _cloth.SpringCount;

    /// <summary>Spring projections in one simulated second: frames x substeps x springs.</summary>
    public double ProjectionsPerSecond => (double)StepsPerSecond * Substeps * SpringCount;

    /// <summary>The runner the world splits its work over (null: one core).</summary>
    public IParallelRunner? Runner
    {
        get => _cloth.System.Runner;
        set => _cloth.System.Runner = value;
    }

    public void Reset() => _cloth.Reset();

    /// <summary>Steps <paramref name="steps"/> frames of 1/60 s.</summary>
    public void Run(int steps)
    {
        for (var s = 0; s < steps; s++)
        {
            _cloth.System.Step(Integrator, FrameTime);
        }
    }

    /// <summary>One simulated second from rest: a reset, then 60 frames.</summary>
    public void SimulateSecond()
    {
        Reset();
        Run(StepsPerSecond);
    }

    /// <summary>The sum of the state [x | v] in order (what <c>cloth_xpbd --run</c> prints).</summary>
    public double Checksum()
    {
        var state = _cloth.System.State;
        var sum = 0.0;
        for (var i = 0; i < state.Length; i++)
        {
            sum += state[i];
        }

        return sum;
    }
}
