using System;
using System.Collections.Generic;
using System.Globalization;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The quality mode (issue 13): what each solver's cloth looks like after <see cref="Seconds"/> s from rest, so that
/// speed is never bought with a wrong cloth. The n x n cloth of <see cref="ClothFixture"/> is run by xpbd (10
/// substeps, the game setting, and 40 and 160 to show where more substeps take it), implicit Euler at 1e-3 and 1e-6 (each at one 60 Hz frame per step) and RK4 at the scenario's default
/// dt (1 ms), against RK4 at <see cref="ReferenceTimeStep"/>, itself compared with RK4 at 2x and 4x its
/// dt. Per solver: the lowest point (min y over the particles), the mean and largest stretch
/// (l - r) / r of the 2 n (n - 1) structural springs (rest length r, computed from the positions), and the largest
/// distance of a particle from where the reference has it. Deterministic: no timing, the same figures on any machine
/// that computes IEEE doubles as this one (every run of this code gives the same bits).
/// </summary>
internal static class ClothQuality
{
    /// <summary>The simulated time from rest: 5 s, the scenario's default duration.</summary>
    public const double Seconds = ClothScenario.DefaultDuration;

    /// <summary>The reference: RK4 at 0.25 ms (a quarter of the default dt, an eighth of RK4's limit on 64 x 64).</summary>
    public const double ReferenceTimeStep = 0.00025;

    /// <summary>A 60 Hz frame.</summary>
    public const double Frame = 1.0 / 60;

    public static int Run(string[] args)
    {
        var n = int.Parse(Program.Option(args, "--n") ?? "64", CultureInfo.InvariantCulture);
        var solvers = new List<(string Name, Func<IIntegrator> Create, double Dt)>
        {
            ("xpbd, 10 substeps", () => new Xpbd(10), Frame),
            ("xpbd, 40 substeps", () => new Xpbd(40), Frame),
            ("xpbd, 160 substeps", () => new Xpbd(160), Frame),
            ("implicit Euler, tolerance 1e-3", () => new ImplicitEuler { Tolerance = 1e-3 }, Frame),
            ("implicit Euler, tolerance 1e-6", () => new ImplicitEuler { Tolerance = 1e-6 }, Frame),
            ("rk4 at the default dt", () => new RungeKutta4(), ClothScenario.DefaultTimeStep),
            ("rk4 (reference x 2)", () => new RungeKutta4(), 2 * ReferenceTimeStep),
        };
        if (n > 64)
        {
            // RK4's limit falls below 1 ms beyond n = 64 (0.37 ms at 128): the default dt diverges there.
            solvers.RemoveAll(s => s.Dt == ClothScenario.DefaultTimeStep);
        }

        Console.WriteLine(string.Create(
            CultureInfo.InvariantCulture,
            $"The {n} x {n} cloth (ClothScenario defaults) after {Seconds} s from rest; reference: rk4 at dt = {ReferenceTimeStep} s."));
        Console.WriteLine("stretch = (l - r) / r over the structural springs; distance = the largest distance of a particle from the reference's.");
        Console.WriteLine();
        var reference = Simulate(n, new RungeKutta4(), ReferenceTimeStep);
        Console.WriteLine("| solver | dt [s] | steps | lowest point [m] | vs reference [m] | mean stretch | largest stretch | distance [m] |");
        Console.WriteLine("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
        Print("rk4 (reference)", reference, reference);
        foreach (var (name, create, dt) in solvers)
        {
            Print(name, Simulate(n, create(), dt), reference);
        }

        return 0;
    }

    private static Outcome Simulate(int n, IIntegrator integrator, double dt)
    {
        var cloth = new ClothFixture(n);
        var steps = (int)Math.Round(Seconds / dt);
        for (var s = 0; s < steps; s++)
        {
            cloth.System.Step(integrator, dt);
        }

        return new Outcome(dt, steps, cloth.System.State.Slice(0, 3 * cloth.ParticleCount).ToArray(), n, cloth.Scenario.Resolution);
    }

    private static void Print(string name, Outcome outcome, Outcome reference)
    {
        var distance = 0.0;
        for (var i = 0; i < outcome.Positions.Length; i += 3)
        {
            var dx = outcome.Positions[i] - reference.Positions[i];
            var dy = outcome.Positions[i + 1] - reference.Positions[i + 1];
            var dz = outcome.Positions[i + 2] - reference.Positions[i + 2];
            distance = Math.Max(distance, Math.Sqrt((dx * dx) + (dy * dy) + (dz * dz)));
        }

        Console.WriteLine(string.Create(
            CultureInfo.InvariantCulture,
            $"| {name} | {outcome.Dt:G6} | {outcome.Steps} | {outcome.LowestPoint:F6} | {outcome.LowestPoint - reference.LowestPoint:+0.0E+0;-0.0E+0;0} | {outcome.MeanStretch:P3} | {outcome.LargestStretch:P2} | {distance:G3} |"));
    }

    /// <summary>A solver's cloth after <see cref="Seconds"/>: its positions and the figures taken from them.</summary>
    private sealed class Outcome
    {
        public Outcome(double dt, int steps, double[] positions, int n, double restLength)
        {
            Dt = dt;
            Steps = steps;
            Positions = positions;
            LowestPoint = double.PositiveInfinity;
            for (var i = 1; i < positions.Length; i += 3)
            {
                LowestPoint = Math.Min(LowestPoint, positions[i]);
            }

            // Structural springs: (row, col)-(row, col + 1) and (row, col)-(row + 1, col), rest length r.
            var sum = 0.0;
            var count = 0;
            var largest = double.NegativeInfinity;
            for (var row = 0; row < n; row++)
            {
                for (var col = 0; col < n; col++)
                {
                    var a = (row * n) + col;
                    if (col + 1 < n)
                    {
                        Add(Stretch(a, a + 1));
                    }

                    if (row + 1 < n)
                    {
                        Add(Stretch(a, a + n));
                    }
                }
            }

            MeanStretch = sum / count;
            LargestStretch = largest;

            void Add(double stretch)
            {
                sum += stretch;
                count++;
                largest = Math.Max(largest, stretch);
            }

            double Stretch(int a, int b)
            {
                var dx = positions[3 * a] - positions[3 * b];
                var dy = positions[(3 * a) + 1] - positions[(3 * b) + 1];
                var dz = positions[(3 * a) + 2] - positions[(3 * b) + 2];
                return (Math.Sqrt((dx * dx) + (dy * dy) + (dz * dz)) - restLength) / restLength;
            }
        }

        public double Dt { get; }

        public int Steps { get; }

        public double[] Positions { get; }

        public double LowestPoint { get; }

        public double MeanStretch { get; }

        public double LargestStretch { get; }
    }
}
