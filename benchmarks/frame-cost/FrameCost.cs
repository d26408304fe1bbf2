// What a 60 Hz frame of the n x n cloth costs, per integrator, on the runtime that runs this program: the first table
// of docs/benchmarks.md. The same source is compiled by Mono's mcs (run on Mono) and by the .NET SDK (FrameCost.csproj,
// run on CoreCLR) against the same netstandard2.1 ParticlePhysics.dll; run.sh beside it does both and prints the
// combined table. Mono cannot run BenchmarkDotNet, hence a plain program.
//
// A frame is 1/60 s of simulated time. Each integrator takes it in the fewest steps that keep it stable on this cloth:
// implicit Euler and xpbd (10 substeps inside its step) in one step, rk45 in one call that chooses its own steps (its
// default tolerance 1e-8), the explicit integrators in ceil((1/60) / dt) steps of equal length, dt their largest
// stable step from stable-time-steps.csv (the benchmarks' stability mode). A round times one simulated second from rest
// (60 frames: the cloth falls and swings, implicit Euler's hardest frames) of every integrator on one thread and on
// WorkerThreadRunner(2), in turn, so that all see the same load; the program prints the fastest and the median round
// per frame in wall time, and for one thread also the fastest in the thread's CPU time, which leaves out the waits
// for a core that a loaded machine adds to the wall time. The two-thread run must give the one-thread bits (checked), and prints a hash of them, which run.sh
// compares across the runtimes.
//
// C# 7.2 at most (mcs -langversion:7.2): no nullable annotations, no file-scoped namespace, no switch expressions.
using System;
using System.Collections.Generic;
using System.Diagnostics;
using System.Globalization;
using System.IO;
using System.Runtime.InteropServices;
using ParticlePhysics.Integrators;
using ParticlePhysics.Parallel;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.FrameCost
{
    /// <summary>Times every integrator's 60 Hz frame on the cloth and prints the results.</summary>
    internal static class Program
    {
        private const double Frame = 1.0 / 60;
        private const int FramesPerRound = 60;

        private static int Main(string[] args)
        {
            var csv = Option(args, "--steps-from", null);
            var n = int.Parse(Option(args, "--n", "64"), CultureInfo.InvariantCulture);
            var rounds = int.Parse(Option(args, "--rounds", "5"), CultureInfo.InvariantCulture);
            if (csv == null || n < 3 || rounds < 1)
            {
                Console.Error.WriteLine("usage: FrameCost --steps-from stable-time-steps.csv [--n 64] [--rounds 5]");
                return 2;
            }

            var stable = ReadStableSteps(csv);
            var cases = new List<Case>();
            foreach (var name in IntegratorCatalog.Names)
            {
                if (name == "implicit-euler")
                {
                    // The game's tolerance (the Unity sample's) and the library's default.
                    cases.Add(new Case(name, 1e-3, "1e-3", 1));
                    cases.Add(new Case(name, 1e-6, "1e-6", 1));
                }
                else if (name == "xpbd" || IntegratorCatalog.IsAdaptive(name))
                {
                    cases.Add(new Case(name, 0, null, 1));
                }
                else
                {
                    cases.Add(new Case(name, 0, null, StepsPerFrame(stable, name, n)));
                }
            }

            Console.WriteLine("runtime " + RuntimeDescription());
            Console.WriteLine(string.Format(
                CultureInfo.InvariantCulture,
                "cloth {0} x {0}, {1} rounds of one simulated second from rest per integrator and thread count, in turn; {2} cores",
                n,
                rounds,
                Environment.ProcessorCount));
            using (var runner = new WorkerThreadRunner(2))
            {
                var runs = new List<Run>();
                foreach (var c in cases)
                {
                    runs.Add(new Run(c, n, null));
                    runs.Add(new Run(c, n, runner));
                }

                foreach (var run in runs)
                {
                    run.Second(); // warm-up: the runtime compiles, the solvers size their buffers
                    run.Times.Clear();
                    run.CpuTimes.Clear();
                }

                for (var round = 0; round < rounds; round++)
                {
                    foreach (var run in runs)
                    {
                        run.Second();
                    }
                }

                for (var i = 0; i < runs.Count; i += 2)
                {
                    var one = runs[i];
                    var two = runs[i + 1];
                    if (one.StateHash != two.StateHash)
                    {
                        Console.Error.WriteLine("error: " + one.Case.Label + " on two threads gives other bits than on one");
                        return 1;
                    }

                    foreach (var run in new[] { one, two })
                    {
                        // frame <case> <threads> <fastest ms> <median ms> <steps per frame> <dt> <fastest CPU ms>
                        // (wall times; the CPU time is the timing thread's, -1 on two threads or where it cannot be read)
                        var cpu = run.Threads == 1 ? Min(run.CpuTimes) : -1;
                        Console.WriteLine(string.Format(
                            CultureInfo.InvariantCulture,
                            "frame {0} {1} {2:F3} {3:F3} {4} {5:R} {6:F3}",
                            run.Case.Label,
                            run.Threads,
                            Min(run.Times) / FramesPerRound,
                            Median(run.Times) / FramesPerRound,
                            run.Case.StepsPerFrame,
                            Frame / run.Case.StepsPerFrame,
                            cpu < 0 ? -1 : cpu / FramesPerRound));
                    }

                    Console.WriteLine("hash " + one.Case.Label + " " + one.StateHash.ToString("x16", CultureInfo.InvariantCulture));
                    if (one.IterationsPerFrame >= 0)
                    {
                        Console.WriteLine(string.Format(CultureInfo.InvariantCulture, "count {0} cg-iterations-per-frame {1:F2}", one.Case.Label, one.IterationsPerFrame));
                    }
                }
            }

            return 0;
        }

        // ceil((1/60) / dt): the fewest equal steps of a frame, none longer than the largest stable dt. A cloth smaller
        // than the tabulated one is less stiff (its springs' frequencies and damping rates grow with n), so its row
        // serves a smaller n too.
        private static int StepsPerFrame(Dictionary<string, SortedDictionary<int, double>> stable, string name, int n)
        {
            SortedDictionary<int, double> sizes;
            if (stable.TryGetValue(name, out sizes))
            {
                foreach (var row in sizes)
                {
                    if (row.Key >= n)
                    {
                        return (int)Math.Ceiling(Frame / row.Value);
                    }
                }
            }

            throw new InvalidOperationException(string.Format(
                CultureInfo.InvariantCulture,
                "no stable dt for {0} at n >= {1} in the CSV: run the benchmarks' stability mode with --n {1} --write",
                name,
                n));
        }

        private static Dictionary<string, SortedDictionary<int, double>> ReadStableSteps(string path)
        {
            var table = new Dictionary<string, SortedDictionary<int, double>>();
            foreach (var line in File.ReadAllLines(path))
            {
                var fields = line.Split(',');
                int n;
                double dt;
                if (fields.Length != 3
                    || !int.TryParse(fields[1], NumberStyles.Integer, CultureInfo.InvariantCulture, out n)
                    || !double.TryParse(fields[2], NumberStyles.Float, CultureInfo.InvariantCulture, out dt))
                {
                    continue; // the header
                }

                SortedDictionary<int, double> sizes;
                if (!table.TryGetValue(fields[0], out sizes))
                {
                    sizes = new SortedDictionary<int, double>();
                    table.Add(fields[0], sizes);
                }

                sizes[n] = dt;
            }

            return table;
        }

        private static string Option(string[] args, string name, string fallback)
        {
            var i = Array.IndexOf(args, name);
            return i >= 0 && i + 1 < args.Length ? args[i + 1] : fallback;
        }

        private static double Min(List<double> values)
        {
            var min = double.PositiveInfinity;
            foreach (var value in values)
            {
                min = Math.Min(min, value);
            }

            return min;
        }

        private static double Median(List<double> values)
        {
            var sorted = values.ToArray();
            Array.Sort(sorted);
            return sorted.Length % 2 == 1 ? sorted[sorted.Length / 2] : 0.5 * (sorted[(sorted.Length / 2) - 1] + sorted[sorted.Length / 2]);
        }

        private static string RuntimeDescription()
        {
            var mono = Type.GetType("Mono.Runtime");
            if (mono != null)
            {
                var display = mono.GetMethod(
                    "GetDisplayName", System.Reflection.BindingFlags.NonPublic | System.Reflection.BindingFlags.Static);
                return "Mono " + (display == null ? "(unknown version)" : Convert.ToString(display.Invoke(null, null), CultureInfo.InvariantCulture));
            }

            return RuntimeInformation.FrameworkDescription;
        }
    }

    /// <summary>One row of the table: an integrator, its tolerance (implicit Euler only; 0: its default) and its steps per frame.</summary>
    internal sealed class Case
    {
        public Case(string name, double tolerance, string toleranceText, int stepsPerFrame)
        {
            Name = name;
            Tolerance = tolerance;
            StepsPerFrame = stepsPerFrame;
            Label = toleranceText == null ? name : name + "@" + toleranceText;
        }

        public string Name { get; }

        public double Tolerance { get; }

        public int StepsPerFrame { get; }

        /// <summary>The name in the output: the integrator's, with "@1e-3" for a tolerance.</summary>
        public string Label { get; }
    }

    /// <summary>One integrator on its own cloth, on one thread or on a runner; <see cref="Second"/> times one simulated second from rest.</summary>
    internal sealed class Run
    {
        private const double Frame = 1.0 / 60;
        private const int FramesPerRound = 60;
        private readonly ParticleWorld _world;
        private readonly double[] _initial;
        private readonly IIntegrator _integrator;
        private readonly double[] _coldState;

        public Run(Case c, int n, IParallelRunner runner)
        {
            Case = c;
            Threads = runner == null ? 1 : runner.MaxParallelism;
            _world = new ClothScenario { Resolution = 1.0 / (n - 1) }.Build();
            _world.Runner = runner;
            _initial = _world.State.ToArray();
            _integrator = IntegratorCatalog.Create(c.Name);
            var implicitEuler = _integrator as ImplicitEuler;
            if (implicitEuler != null && c.Tolerance > 0)
            {
                implicitEuler.Tolerance = c.Tolerance;
            }

            // Each second starts the integrator cold, as a new simulation would: the state of a fresh one, read back.
            var stateful = _integrator as IStatefulIntegrator;
            if (stateful != null)
            {
                _coldState = new double[stateful.StateLength];
                stateful.WriteState(_coldState);
            }

            Times = new List<double>();
            CpuTimes = new List<double>();
            IterationsPerFrame = -1;
        }

        public Case Case { get; }

        public int Threads { get; }

        /// <summary>The wall time of each timed second, in milliseconds.</summary>
        public List<double> Times { get; }

        /// <summary>The calling thread's CPU time of each timed second, in milliseconds (-1 where it cannot be read).</summary>
        public List<double> CpuTimes { get; }

        /// <summary>FNV-1a of the raw bits of the state after the last second.</summary>
        public ulong StateHash { get; private set; }

        /// <summary>Implicit Euler's conjugate-gradient iterations per frame in the last second (-1 for the others).</summary>
        public double IterationsPerFrame { get; private set; }

        /// <summary>One simulated second from rest (60 frames); adds its wall and CPU times to <see cref="Times"/> and <see cref="CpuTimes"/>.</summary>
        public void Second()
        {
            _world.SetState(_initial);
            _world.Time = 0;
            if (_coldState != null)
            {
                ((IStatefulIntegrator)_integrator).ReadState(_coldState);
            }

            var implicitEuler = _integrator as ImplicitEuler;
            long iterations = 0;
            var dt = Frame / Case.StepsPerFrame;
            var cpuStart = ThreadCpu.Milliseconds();
            var clock = Stopwatch.StartNew();
            for (var frame = 0; frame < FramesPerRound; frame++)
            {
                for (var step = 0; step < Case.StepsPerFrame; step++)
                {
                    _world.Step(_integrator, dt);
                }

                if (implicitEuler != null)
                {
                    iterations += implicitEuler.LastIterations;
                }
            }

            var milliseconds = clock.Elapsed.TotalMilliseconds;
            var cpuEnd = ThreadCpu.Milliseconds();
            if (implicitEuler != null)
            {
                IterationsPerFrame = (double)iterations / FramesPerRound;
            }

            var hash = 14695981039346656037UL;
            foreach (var value in _world.State.ToArray())
            {
                var bits = BitConverter.DoubleToInt64Bits(value);
                for (var b = 0; b < 64; b += 8)
                {
                    hash = unchecked((hash ^ (ulong)((bits >> b) & 0xff)) * 1099511628211UL);
                }
            }

            StateHash = hash;
            Times.Add(milliseconds);
            CpuTimes.Add(cpuStart < 0 || cpuEnd < 0 ? -1 : cpuEnd - cpuStart);
        }
    }

    /// <summary>
    /// The calling thread's CPU time (getrusage RUSAGE_THREAD on Linux, microseconds), which leaves out the time the thread
    /// waited for a core; -1 where it cannot be read.
    /// </summary>
    internal static class ThreadCpu
    {
        private const int RusageThread = 1;

        public static double Milliseconds()
        {
            try
            {
                ResourceUsage usage;
                if (getrusage(RusageThread, out usage) != 0)
                {
                    return -1;
                }

                return ((usage.UserSeconds + usage.SystemSeconds) * 1000.0) + ((usage.UserMicroseconds + usage.SystemMicroseconds) / 1000.0);
            }
            catch (DllNotFoundException)
            {
                return -1;
            }
            catch (EntryPointNotFoundException)
            {
                return -1;
            }
        }

        [DllImport("libc", SetLastError = true)]
        private static extern int getrusage(int who, out ResourceUsage usage);

        // struct rusage on 64-bit Linux: two struct timeval (ru_utime, ru_stime), then 14 longs.
        [StructLayout(LayoutKind.Sequential)]
        private struct ResourceUsage
        {
            public long UserSeconds;
            public long UserMicroseconds;
            public long SystemSeconds;
            public long SystemMicroseconds;
            public long MaxResidentSetSize;
            public long SharedMemory;
            public long UnsharedData;
            public long UnsharedStack;
            public long MinorFaults;
            public long MajorFaults;
            public long Swaps;
            public long BlocksIn;
            public long BlocksOut;
            public long MessagesSent;
            public long MessagesReceived;
            public long Signals;
            public long VoluntarySwitches;
            public long InvoluntarySwitches;
        }
    }
}
