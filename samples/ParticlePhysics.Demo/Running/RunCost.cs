using System;
using System.Collections.Generic;
using System.Globalization;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Demo.Running;

/// <summary>
/// What a run will cost, said before it starts when it is long or large: its steps, an estimate of its time and of
/// the memory it holds. The time is steps x (per step + particles x per particle + springs x per spring), with the
/// three costs of each integrator measured by the benchmark program's <c>costs</c> mode (see <see cref="_costs"/>);
/// the memory adds up the arrays the core and the demo allocate for the world, its springs, the integrator's scratch
/// buffers and the rows (a test measures it against the garbage collector's count).
/// </summary>
internal sealed record RunCost(long Steps, int Particles, long Springs, double Seconds, long Bytes)
{
    /// <summary>A run expected to take at least this long (in s) is announced.</summary>
    public const double NoteSeconds = 10;

    /// <summary>A run expected to hold at least this much memory (1 GiB) is announced.</summary>
    public const long NoteBytes = 1L << 30;

    // Nanoseconds per step, per particle and per spring for each integrator: `dotnet run -c Release --project
    // benchmarks/ParticlePhysics.Benchmarks -- costs` (the fastest of 200 batches on one free particle, 4,096 free
    // particles and the 64 x 64 cloth at dt = 1 ms), 2026-12-01 on the 2-core development machine under load (about
    // 1.7 times the quiet machine's times in c54a830's docs/benchmarks.md: 287 us against 166 us for an explicit cloth
    // step), so the estimates lean long. Implicit Euler's and rk45's costs depend on dt and the stiffness (iterations,
    // internal steps): theirs are those of the cloth at its default 1 ms.
    private static readonly Dictionary<string, (double Step, double Particle, double Spring)> _costs = new()
    {
        ["explicit-euler"] = (50, 24.00, 7.90),
        ["semi-implicit-euler"] = (47, 13.11, 8.26),
        ["implicit-euler"] = (189, 67.95, 139.76),
        ["rk4"] = (150, 53.83, 33.58),
        ["velocity-verlet"] = (72, 17.41, 17.31),
        ["rk45"] = (366, 175.15, 149.38),
    };

    // Bytes per particle of each integrator's scratch buffers (Integrators/*.cs): 8 bytes per double of 3 or 6 per particle.
    private static readonly Dictionary<string, int> _integratorBytes = new()
    {
        ["explicit-euler"] = 48,        // the slope, 6 doubles
        ["semi-implicit-euler"] = 24,   // the accelerations, 3
        ["implicit-euler"] = 312,       // 8 vectors of 3, the 3 x 3 blocks (9), two warm-start vectors of 3
        ["rk4"] = 96,                   // k and the stage, 6 each
        ["velocity-verlet"] = 72,       // two accelerations and a predicted velocity, 3 each
        ["rk45"] = 432,                 // seven stages, y and the stage, 6 each
    };

    /// <summary>True when the run is long or large enough to say what it costs before it starts.</summary>
    public bool IsWorthSaying => Seconds >= NoteSeconds || Bytes >= NoteBytes;

    /// <summary>The estimate for <paramref name="setup"/> run as <paramref name="plan"/> says.</summary>
    public static RunCost For(ScenarioSetup setup, RunPlan plan)
    {
        var particles = (setup as IParticleRun)?.ParticleCount ?? 0;
        long springs = setup switch
        {
            ClothSetup cloth => ClothScenario.SpringCount(cloth.ParticlesPerSide),
            SceneSetup scene => scene.SpringCount,
            ParticleSetup => particles, // a chain's or an anchor's few springs
            _ => 0,
        };
        var (step, particle, spring) = _costs.TryGetValue(plan.Integrator, out var c) ? c : _costs["rk4"];
        var seconds = plan.Steps * (step + (particles * particle) + (springs * spring)) * 1e-9;
        return new RunCost(plan.Steps, particles, springs, seconds, Memory(setup, plan.Integrator, particles, springs));
    }

    /// <summary>
    /// The bytes the run holds: the world (state and scratch state 48 + 48, masses and inverse masses 8 + 8, pins 1,
    /// forces 24 per particle), the springs (two ends and k, L, c: 32 bytes each, in arrays that double as they grow;
    /// implicit Euler adds its linearisation, 40 each), the integrator's scratch, and the demo's rows and column names.
    /// </summary>
    public static long Memory(ScenarioSetup setup, string integrator, int particles, long springs)
    {
        var capacity = springs == 0 ? 0 : CeilingPowerOfTwo(springs);
        var springBytes = (32 + (integrator == "implicit-euler" ? 40 : 0)) * capacity;
        var integratorBytes = (long)(_integratorBytes.TryGetValue(integrator, out var b) ? b : 96) * particles;
        if (integrator == "implicit-euler" && particles >= ImplicitEuler.MultigridThreshold && springs > 0)
        {
            // The multigrid preconditioner (Integrators/Multigrid/): 8 ints per coupling (the pairs, their
            // copy for the change check, the two block targets and the assembly's masked targets), and per particle the
            // aggregation maps and the coarse levels' 3 x 3 blocks (about a quarter as many rows per level, some nine
            // blocks each): 320 bytes, from the 64 x 64 cloth's 2.05 MB that the measurement below found beyond the rest.
            integratorBytes += (32L * springs) + (320L * particles);
        }

        // The demo's rows: the column names (an array and the strings), a row, and the exact state when there is one.
        long demo = 0;
        if (setup is ParticleSetup rows)
        {
            demo = 48 + (16L * rows.ColumnCount) + rows.ColumnNameBytes() + (setup.Exact is null ? 0 : 48L * particles);
        }
        else if (setup is SceneSetup)
        {
            // 6 columns per particle, 8 bytes in the row and about 40 bytes of name each.
            demo = 48 + (288L * particles);
        }

        return (137L * particles) + springBytes + integratorBytes + demo;
    }

    /// <summary>The line to print on stderr: what the run is, and what it will cost.</summary>
    public string Note(string scenario, RunPlan plan) => string.Format(
        CultureInfo.InvariantCulture,
        "note: {0} will take {1:N0} step{2} of {3:R} s with {4} on {5:N0} particles and {6:N0} springs: about {7} "
        + "(from the per-step costs measured by the benchmarks' costs mode) and {8} of memory.",
        scenario,
        Steps,
        Steps == 1 ? string.Empty : "s",
        plan.Dt,
        plan.Integrator,
        Particles,
        Springs,
        Duration(Seconds),
        Size(Bytes));

    private static long CeilingPowerOfTwo(long n)
    {
        // ForceElements grows from 8 by doubling, so it holds the first 8 x 2^k at or above the count.
        long capacity = 8;
        while (capacity < n)
        {
            capacity *= 2;
        }

        return capacity;
    }

    private static string Duration(double seconds) => seconds switch
    {
        < 120 => string.Format(CultureInfo.InvariantCulture, "{0:0} s", seconds),
        < 7200 => string.Format(CultureInfo.InvariantCulture, "{0:0} min", seconds / 60),
        < 172800 => string.Format(CultureInfo.InvariantCulture, "{0:0} h", seconds / 3600),
        _ => string.Format(CultureInfo.InvariantCulture, "{0:0} days", seconds / 86400),
    };

    private static string Size(long bytes) => bytes switch
    {
        < 1L << 20 => string.Format(CultureInfo.InvariantCulture, "{0:0} kB", bytes / 1e3),
        < 1L << 30 => string.Format(CultureInfo.InvariantCulture, "{0:0} MB", bytes / 1e6),
        _ => string.Format(CultureInfo.InvariantCulture, "{0:0.0} GB", bytes / 1e9),
    };
}
