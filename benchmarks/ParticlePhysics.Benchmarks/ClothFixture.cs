using System;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The course's n x n cloth (<see cref="ClothScenario"/> with its defaults, resolution 1 / (n - 1)) and its initial
/// state, so that every benchmark invocation starts from the same flat cloth at rest.
/// </summary>
/// <remarks>
/// Why a reset: at dt = 1 ms the explicit integrators are at or past their stability limit on the finer cloths
/// (see the stability mode), and a benchmark runs hundreds of thousands of steps; stepping one system for that long
/// would end in divergence or measure a cloth that has come to rest. Each invocation therefore runs
/// <see cref="StepsPerInvoke"/> steps from the initial state: <see cref="Reset"/> (SetState, a checked copy of 6 N
/// doubles) costs well under 1 % of 16 RK4 steps, and the <c>Reset</c> benchmark measures it so it can be subtracted.
/// </remarks>
internal sealed class ClothFixture
{
    /// <summary>The steps run by one benchmark invocation before the state is reset (the OperationsPerInvoke).</summary>
    public const int StepsPerInvoke = 16;

    /// <summary>The time step of the cloth benchmarks, the scenario's default: 1 ms.</summary>
    public const double TimeStep = ClothScenario.DefaultTimeStep;

    private readonly double[] _initial;

    public ClothFixture(int particlesPerSide)
    {
        if (particlesPerSide < 3)
        {
            throw new ArgumentOutOfRangeException(nameof(particlesPerSide), particlesPerSide, "n must be at least 3.");
        }

        ParticlesPerSide = particlesPerSide;
        Scenario = new ClothScenario { Resolution = 1.0 / (particlesPerSide - 1) };
        System = Scenario.Build();
        _initial = System.State.ToArray();
    }

    public int ParticlesPerSide { get; }

    public int ParticleCount => ParticlesPerSide * ParticlesPerSide;

    public int SpringCount => ClothScenario.SpringCount(ParticlesPerSide);

    public ClothScenario Scenario { get; }

    public ParticleSystem System { get; }

    /// <summary>The initial state [positions | velocities]: the flat cloth at rest.</summary>
    public ReadOnlySpan<double> InitialState => _initial;

    /// <summary>Puts the cloth back into its initial state at t = 0.</summary>
    public void Reset()
    {
        System.SetState(_initial);
        System.Time = 0;
    }
}
