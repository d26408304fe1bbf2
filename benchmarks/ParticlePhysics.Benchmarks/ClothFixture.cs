using System;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The course's n x n cloth (<see cref="ClothScenario"/> with its defaults, resolution 1 / (n - 1)) and its initial
/// state, so that every benchmark invocation starts from the same flat cloth at rest.
/// </summary>
/// <remarks>
/// Why a reset: a benchmark runs hundreds of thousands of steps; stepping one system for that long would measure a
/// cloth that has come to rest, or, for an integrator near its stability limit, end in divergence. Each invocation therefore runs
/// <see cref="StepsPerInvoke"/> steps from the initial state: <see cref="Reset"/> (SetState, a checked copy of 6 N
/// doubles) costs well under 1 % of 16 RK4 steps, and the <c>Reset</c> benchmark measures it so it can be subtracted.
/// </remarks>
internal sealed class ClothFixture
{
    /// <summary>The steps run by one benchmark invocation before the state is reset (the OperationsPerInvoke).</summary>
    public const int StepsPerInvoke = 16;

    /// <summary>
    /// The RK4 step of the n x n cloth benchmarks: the scenario's default 1 ms up to n = 64, then 1 ms (64 / n)^2
    /// (0.25 ms at n = 128, 62.5 us at n = 256).
    /// </summary>
    /// <remarks>
    /// With M = 1 kg spread over n^2 particles and k, c fixed per spring, a particle's spring frequency grows as
    /// sqrt(k n^2 / M) ~ n but its axial damping rate c n^2 / M grows as n^2, so RK4's limit (for a damped mode, the
    /// real-axis bound 2.78 / rate) falls faster than 1 / n. The stability mode measures the limit at 2.0 ms for
    /// n = 64 and 0.37 ms for n = 128 (1 ms diverges within 16 steps there: the state passes 1e26); at n = 256 a
    /// search takes too long, and 16 steps from rest diverge at 0.25 ms but not at 0.125 ms. 1 ms (64 / n)^2
    /// (0.25 ms, 62.5 us) stays inside the limit, so the measured state is finite and physical; the cost of a step
    /// does not depend on dt (no branch does, but l = 0). The C reference uses the same rule.
    /// </remarks>
    public static double Rk4TimeStep(int particlesPerSide) =>
        particlesPerSide <= 64
            ? ClothScenario.DefaultTimeStep
            : ClothScenario.DefaultTimeStep * (64.0 / particlesPerSide) * (64.0 / particlesPerSide);

    private readonly double[] _initial;

    public ClothFixture(int particlesPerSide)
        : this(particlesPerSide, new ClothScenario().Damping)
    {
    }

    /// <summary>The cloth with the springs' axial damping <paramref name="damping"/> (N s/m) instead of the scenario's.</summary>
    public ClothFixture(int particlesPerSide, double damping)
    {
        if (particlesPerSide < 3)
        {
            throw new ArgumentOutOfRangeException(nameof(particlesPerSide), particlesPerSide, "n must be at least 3.");
        }

        ParticlesPerSide = particlesPerSide;
        TimeStep = Rk4TimeStep(particlesPerSide);
        Scenario = new ClothScenario { Resolution = 1.0 / (particlesPerSide - 1), Damping = damping };
        System = Scenario.Build();
        _initial = System.State.ToArray();
    }

    public int ParticlesPerSide { get; }

    /// <summary>The RK4 time step of this cloth: <see cref="Rk4TimeStep"/>.</summary>
    public double TimeStep { get; }

    public int ParticleCount => ParticlesPerSide * ParticlesPerSide;

    public int SpringCount => ClothScenario.SpringCount(ParticlesPerSide);

    public ClothScenario Scenario { get; }

    public ParticleWorld System { get; }

    /// <summary>The initial state [positions | velocities]: the flat cloth at rest.</summary>
    public ReadOnlySpan<double> InitialState => _initial;

    /// <summary>Puts the cloth back into its initial state at t = 0.</summary>
    public void Reset()
    {
        System.SetState(_initial);
        System.Time = 0;
    }
}
