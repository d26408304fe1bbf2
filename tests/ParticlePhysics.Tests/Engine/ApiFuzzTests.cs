using System;
using System.Collections.Generic;
using System.Diagnostics;
using System.Globalization;
using System.IO;
using System.Linq;
using System.Numerics;
using ParticlePhysics.Constraints;
using ParticlePhysics.Contacts;
using ParticlePhysics.Driver;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Snapshots;
using ParticlePhysics.Tests.Support;
using Xunit.Abstractions;

namespace ParticlePhysics.Tests.Engine;

/// <summary>
/// Issue 10: long random sequences of public operations on small worlds (particles, masses, pins, states, times, limits,
/// springs, dampers, forces added and removed, integrators switched between steps and retuned, snapshots, a fixed-step
/// driver, rods, contacts, a kinematic body and kinematic moves in durations down to double.Epsilon), with invalid values
/// and with user forces that throw or write NaN or infinity. Issue 27: a force, the contacts' pair filter or a
/// constraint set that steps the world, or advances its driver, from inside the world's own step (armed like a fault).
/// Every operation runs on two twin worlds built alike; only the first twin's faults are ever armed. Checked after
/// every operation:
/// <list type="bullet">
/// <item>the twins agree: the same outcome (the same exception, or none) and bit-identical state, masses, pins, time,
/// integrator states and driver;</item>
/// <item>a rejected call changed nothing, bit for bit;</item>
/// <item>a call that failed because of a fault left the first twin as it was, and its retry, without the fault (half of
/// the time after restoring a snapshot taken before the call), equals the clean twin's call: the same step taken from
/// the last good state;</item>
/// <item>the world's invariants: every value finite, every mass positive with a finite inverse, 1 / m or 0 (pinned)
/// as inverse mass;</item>
/// <item>nothing throws but the documented exceptions (ArgumentException and its kin, InvalidOperationException,
/// SimulationDivergedException, SolverNotConvergedException).</item>
/// <item>issue 27: physical probes, small worlds of their own held to what the docs promise (a particle on an incline
/// under every integrator, a moving thin obstacle, particles spawned at one point).</item>
/// </list>
/// The fixed seed runs in CI; a longer run on demand: PARTICLEPHYSICS_FUZZ_OPERATIONS=1000000 (and
/// PARTICLEPHYSICS_FUZZ_SEED=n for another sequence), see docs/architecture.md.
/// </summary>
public class ApiFuzzTests
{
    /// <summary>The environment variable that sets the number of operations (default <see cref="DefaultOperations"/>).</summary>
    public const string OperationsVariable = "PARTICLEPHYSICS_FUZZ_OPERATIONS";

    /// <summary>The environment variable that sets the seed (default <see cref="DefaultSeed"/>).</summary>
    public const string SeedVariable = "PARTICLEPHYSICS_FUZZ_SEED";

    public const int DefaultOperations = 10_000;
    public const ulong DefaultSeed = 20261201;

    private readonly ITestOutputHelper _output;

    public ApiFuzzTests(ITestOutputHelper output)
    {
        _output = output;
    }

    [Fact]
    public void Random_public_operations_are_all_or_nothing_and_a_failed_step_retried_equals_the_clean_twins_step()
    {
        var operations = Environment.GetEnvironmentVariable(OperationsVariable) is { Length: > 0 } o
            ? int.Parse(o, CultureInfo.InvariantCulture)
            : DefaultOperations;
        var seed = Environment.GetEnvironmentVariable(SeedVariable) is { Length: > 0 } s
            ? ulong.Parse(s, CultureInfo.InvariantCulture)
            : DefaultSeed;

        var fuzzer = new Fuzzer(seed);
        var cpu = Process.GetCurrentProcess().TotalProcessorTime;
        fuzzer.Run(operations);
        _output.WriteLine(fuzzer.Report());
        _output.WriteLine($"{(Process.GetCurrentProcess().TotalProcessorTime - cpu).TotalSeconds:F1} s of CPU time");

        // The run must have reached what it is there to check, not only the easy paths.
        Assert.Equal(operations, fuzzer.Operations);
        Assert.True(fuzzer.Rejections > operations / 10, fuzzer.Report());
        Assert.True(fuzzer.Steps > operations / 10, fuzzer.Report());
        Assert.True(fuzzer.FailedSteps > 50, fuzzer.Report());
        Assert.True(fuzzer.FaultFailures > 30, fuzzer.Report());
        Assert.True(fuzzer.Retries > 50, fuzzer.Report());
        Assert.True(fuzzer.StepsWithImpacts > operations / 200, fuzzer.Report());
        Assert.True(fuzzer.NestedRefusals > operations / 1000, fuzzer.Report());
        Assert.True(fuzzer.TinyDurationMoves > operations / 1000, fuzzer.Report());
        Assert.True(fuzzer.Probes > operations / 100, fuzzer.Report());
    }

    /// <summary>What <see cref="Twin.Observe()"/> saw, compared byte for byte.</summary>
    private readonly struct Observation : IEquatable<Observation>
    {
        private readonly byte[] _bytes;

        public Observation(byte[] bytes)
        {
            _bytes = bytes;
        }

        public static bool operator ==(Observation a, Observation b) => a.Equals(b);

        public static bool operator !=(Observation a, Observation b) => !a.Equals(b);

        public bool Equals(Observation other) => _bytes.AsSpan().SequenceEqual(other._bytes);

        public override bool Equals(object? obj) => obj is Observation other && Equals(other);

        public override int GetHashCode() => _bytes.Length;
    }

    /// <summary>Two twin worlds and the random operations applied to both.</summary>
    private sealed class Fuzzer
    {
        private const int SequenceLength = 400;
        private const int MaxParticles = 10;
        private readonly SeededRandom _random;
        private readonly ulong _seed;
        private readonly Queue<string> _log = new();
        private Twin _a = null!;
        private Twin _b = null!;
        private int _sequence;
        private bool _tinyDuration; // the operation being drawn moves a kinematic particle in less than 1 / double.MaxValue s

        public Fuzzer(ulong seed)
        {
            _seed = seed;
            _random = new SeededRandom(seed);
        }

        public int Operations { get; private set; }

        public int Rejections { get; private set; }

        public int Steps { get; private set; }

        public int FailedSteps { get; private set; }

        public int FaultFailures { get; private set; }

        public int Retries { get; private set; }

        public int SnapshotRoundTrips { get; private set; }

        /// <summary>Calls refused because an armed nesting called the world back from inside its step (issue 27, item 1).</summary>
        public int NestedRefusals { get; private set; }

        /// <summary>
        /// Kinematic moves with a duration whose inverse overflows that reached the velocities (issue 27, items 2 and 3):
        /// accepted, or refused for a velocity that overflows.
        /// </summary>
        public int TinyDurationMoves { get; private set; }

        /// <summary>Worlds of their own built and checked against a physical promise (inclines, moving obstacles, coincident spawns).</summary>
        public int Probes { get; private set; }

        public Dictionary<string, int> RejectionsByType { get; } = new();

        /// <summary>Steps after which the contact set had logged impacts (so that its log was there to keep or restore).</summary>
        public int StepsWithImpacts { get; private set; }

        public string Report() => string.Format(
            CultureInfo.InvariantCulture,
            "seed {0}: {1} operations in {2} sequences, {3} rejected ({4}), {5} steps of which {6} failed, {7} failures "
            + "caused by an armed fault, {8} retries that matched the clean twin, {9} snapshot round trips, {10} steps with impacts logged, "
            + "{11} calls refused for a nested call into the world, {12} kinematic moves in less than 1 / double.MaxValue s that reached the velocities, "
            + "{13} physical probes",
            _seed,
            Operations,
            _sequence,
            Rejections,
            string.Join(", ", RejectionTypes()),
            Steps,
            FailedSteps,
            FaultFailures,
            Retries,
            SnapshotRoundTrips,
            StepsWithImpacts,
            NestedRefusals,
            TinyDurationMoves,
            Probes);

        public void Run(int operations)
        {
            for (var i = 0; i < operations; i++)
            {
                if (i % SequenceLength == 0)
                {
                    NewSequence();
                }

                var (name, apply) = NextOperation();
                Operations++;
                Apply(name, apply);
            }
        }

        private IEnumerable<string> RejectionTypes()
        {
            var names = new List<string>(RejectionsByType.Keys);
            names.Sort(StringComparer.Ordinal);
            foreach (var name in names)
            {
                yield return $"{name} {RejectionsByType[name]}";
            }
        }

        private void NewSequence()
        {
            _sequence++;
            var particles = _random.Next(1, 6);
            var setup = new List<(Vector3d, Vector3d, double)>();
            for (var i = 0; i < particles; i++)
            {
                setup.Add((Clean(-1, 1), Clean(-0.5, 0.5), _random.Between(0.1, 2)));
            }

            _a = new Twin(setup);
            _b = new Twin(setup);
            _log.Clear();
        }

        /// <summary>Runs one operation on both twins and checks everything the class describes.</summary>
        private void Apply(string name, Action<Twin> apply)
        {
            Remember(name);
            var beforeA = _a.Observe();
            var beforeB = _b.Observe();
            Expect(beforeA == beforeB, "the twins differ before the operation");

            var armed = _a.IsArmed;
            (SimulationSnapshot World, double[][] Integrators)? saved = armed ? _a.Save() : null;
            var tinyDuration = _tinyDuration;
            var failureA = Attempt(apply, _a);
            var attempts = $"first twin: {Describe(failureA)}";
            if (armed && failureA is InvalidOperationException && failureA.Message.Contains("during its own step", StringComparison.Ordinal))
            {
                NestedRefusals++;
            }

            if (armed && failureA is not null)
            {
                // The call failed with a fault armed: the first twin must be as it was, and a retry without the fault
                // (from a restored snapshot, half of the time) must do what the clean twin does.
                Expect(_a.Observe() == beforeA, $"a call that failed with a fault armed ({Describe(failureA)}) changed the world");
                _a.Disarm();
                if (_random.Chance(0.5))
                {
                    attempts += ", restored from the snapshot";
                    _a.Restore(saved!.Value);
                    Expect(_a.Observe() == beforeA, "restoring the snapshot taken before the failed call changed the world");
                }

                var first = Describe(failureA);
                failureA = Attempt(apply, _a);
                attempts += $", retried without the fault: {Describe(failureA)}";
                Retries++;
                if (Describe(failureA) != first)
                {
                    FaultFailures++; // the fault was what made it fail
                }
            }

            var failureB = Attempt(apply, _b);
            attempts += $"; clean twin: {Describe(failureB)}";
            Expect(
                Describe(failureA) == Describe(failureB),
                $"the twins disagree: {Describe(failureA)} against {Describe(failureB)}");
            if (tinyDuration && (failureA is null || (failureA is ArgumentOutOfRangeException { ParamName: "duration" } && failureA.Message.Contains("velocity", StringComparison.Ordinal))))
            {
                TinyDurationMoves++;
            }

            if (failureA is not null)
            {
                Rejections++;
                var type = failureA.GetType().Name;
                RejectionsByType[type] = RejectionsByType.TryGetValue(type, out var n) ? n + 1 : 1;
                Expect(_a.Observe() == beforeA, $"a rejected call ({Describe(failureA)}) changed the world");
                Expect(_b.Observe() == beforeB, $"a rejected call ({Describe(failureB)}) changed the clean twin");
                if (name.StartsWith("step", StringComparison.Ordinal) || name.StartsWith("advance", StringComparison.Ordinal))
                {
                    FailedSteps++;
                }
            }

            if (name.StartsWith("step", StringComparison.Ordinal) || name.StartsWith("advance", StringComparison.Ordinal))
            {
                Steps++;
                StepsWithImpacts += _a.Contacts.ImpactCount > 0 ? 1 : 0;
            }

            Expect(_a.Observe() == _b.Observe(), $"the twins differ after the operation ({attempts}), in {Twin.Difference(_a, _b)}");
            _a.CheckInvariants(Expect);
        }

        private Exception? Attempt(Action<Twin> apply, Twin twin)
        {
            try
            {
                apply(twin);
                return null;
            }
            catch (Exception e) when (e is ArgumentException or InvalidOperationException or SimulationDivergedException or SolverNotConvergedException)
            {
                return e;
            }
            catch (Xunit.Sdk.XunitException)
            {
                throw; // a probe's own failure, already reported with the seed and the last operations
            }
            catch (Exception e)
            {
                Fail($"an undocumented exception: {e}");
                throw;
            }
        }

        private static string Describe(Exception? e) => e is null ? "no exception" : $"{e.GetType().Name}: {e.Message}";

        private void Expect(bool condition, string what)
        {
            if (!condition)
            {
                Fail(what);
            }
        }

        private void Fail(string what) =>
            Assert.Fail($"{what}\nseed {_seed}, operation {Operations} (sequence {_sequence}); the last operations:\n  {string.Join("\n  ", _log)}");

        private void Remember(string operation)
        {
            _log.Enqueue(operation);
            if (_log.Count > 25)
            {
                _ = _log.Dequeue();
            }
        }

        private Vector3d Vector(double low, double high) =>
            new(_random.Value(low, high, 0.02), _random.Value(low, high, 0.02), _random.Value(low, high, 0.02));

        private Vector3d Clean(double low, double high) =>
            new(_random.Between(low, high), _random.Between(low, high), _random.Between(low, high));

        private int Index() => _random.Next(-1, _a.World.Count + 1);

        /// <summary>A pinned particle of the first twin (the twins agree), or any index when none is pinned.</summary>
        private int PinnedIndex()
        {
            var pinned = Enumerable.Range(0, _a.World.Count).Where(_a.World.IsPinned).ToArray();
            return pinned.Length > 0 ? _random.Pick(pinned) : Index();
        }

        /// <summary>The next operation: its description and what it does to a twin, every argument drawn once.</summary>
        private (string Name, Action<Twin> Apply) NextOperation()
        {
            var r = _random;
            _tinyDuration = false;
            switch (r.Next(123))
            {
                case < 5 when _a.World.Count < MaxParticles:
                    {
                        var (p, v, m) = (Vector(-2, 2), Vector(-1, 1), r.Value(0.2, 3));
                        return ($"add particle {p} {v} m={G(m)}", t => t.World.AddParticle(p, v, m));
                    }

                case < 9:
                    {
                        var (i, p) = (Index(), Vector(-2, 2));
                        return ($"set position {i} {p}", t => t.World.SetPosition(i, p));
                    }

                case < 13:
                    {
                        var (i, v) = (Index(), Vector(-1, 1));
                        return ($"set velocity {i} {v}", t => t.World.SetVelocity(i, v));
                    }

                case < 16:
                    {
                        var (i, m) = (Index(), r.Value(0.2, 3));
                        return ($"set mass {i} {G(m)}", t => t.World.SetMass(i, m));
                    }

                case < 18:
                    {
                        var i = Index();
                        return ($"pin {i}", t => t.World.Pin(i));
                    }

                case < 20:
                    {
                        var i = Index();
                        return ($"unpin {i}", t => t.World.Unpin(i));
                    }

                case < 22:
                    {
                        var state = _a.World.State.ToArray();
                        if (state.Length > 0)
                        {
                            state[r.Next(state.Length)] = r.Value(-2, 2, 0.5);
                        }

                        if (r.Chance(0.1))
                        {
                            Array.Resize(ref state, Math.Max(0, state.Length + r.Pick(-3, 3)));
                        }

                        return ($"set state ({state.Length} values)", t => t.World.SetState(state));
                    }

                case < 23:
                    {
                        var time = r.Chance(0.3) ? r.Pick(double.MaxValue, 1e300, -1e300, double.NaN, 1e20) : r.Value(0, 10);
                        return ($"set time {G(time)}", t => t.World.Time = time);
                    }

                case < 24:
                    {
                        var limit = r.Chance(0.8) ? ParticleWorld.DefaultDivergenceLimit : r.Value(1, 100, 0.3);
                        return ($"set divergence limit {G(limit)}", t => t.World.DivergenceLimit = limit);
                    }

                case < 28:
                    {
                        var (i, j, k, l, c) = (Index(), Index(), r.Value(0, 20), r.Value(0, 1), r.Value(0, 0.5));
                        return ($"add spring {i}-{j} k={G(k)} L={G(l)} c={G(c)}", t => t.Springs.Add(i, j, k, l, c));
                    }

                case < 29:
                    {
                        var (i, anchor, k, l) = (Index(), Vector(-1, 1), r.Value(0, 40), r.Value(0, 1));
                        return ($"add anchored spring {i} {anchor} k={G(k)} L={G(l)}", t => t.Springs.AddAnchored(i, anchor, k, l));
                    }

                case < 31:
                    {
                        var (s, k) = (r.Next(-1, _a.Springs.Count + 1), r.Value(0, 80));
                        return ($"set stiffness {s} {G(k)}", t => t.Springs.SetStiffness(s, k));
                    }

                case < 32:
                    {
                        var (i, j, k) = (Index(), Index(), r.Value(0, 20));
                        return ($"add zero-length spring {i}-{j} k={G(k)}", t => t.Zero.Add(i, j, k));
                    }

                case < 33:
                    {
                        var (i, j, c) = (Index(), Index(), r.Value(0, 1));
                        return ($"add damper {i}-{j} c={G(c)}", t => t.Dampers.Add(i, j, c));
                    }

                case < 36:
                    {
                        var g = r.Next(Twin.GeneratorCount);
                        return ($"toggle force {g}", t => t.Toggle(g));
                    }

                case < 37:
                    {
                        // Another world's generator is refused only when it names particles (springs, dampers): those
                        // that do not (gravity, drag, the user forces) may be shared, so they are not offered here.
                        var other = r.Chance(0.5);
                        var g = other ? r.Next(2, 5) : r.Next(Twin.GeneratorCount);
                        return (other ? $"add the other twin's force {g}" : $"add force {g} again", t => t.AddAgain(g, other ? Other(t) : t));
                    }

                case < 41:
                    {
                        // Arms the first twin's faults only: the clean twin runs the same operations without them.
                        var (fault, after, particle, jacobian) = (r.Pick(Fault.Throw, Fault.NaN, Fault.Infinity), r.Next(0, 4), r.Next(0, 6), r.Chance(0.3));
                        return ($"arm {(jacobian ? "jacobian" : fault.ToString())} after {after} at {particle}", t =>
                        {
                            if (ReferenceEquals(t, _a))
                            {
                                t.Arm(fault, after, particle, jacobian);
                            }
                        }
                        );
                    }

                case < 66:
                    {
                        var (k, dt) = (r.Next(Twin.IntegratorCount), r.Chance(0.06) ? r.Pick(0.0, -0.01, double.NaN, double.PositiveInfinity, 1e300, 5e-324, 10.0) : r.Between(1e-4, 0.01));
                        return ($"step {Twin.IntegratorName(k)} dt={G(dt)}", t => t.World.Step(t.Integrators[k], dt));
                    }

                case < 70:
                    {
                        var k = r.Next(Twin.IntegratorCount);
                        var stream = r.Chance(0.5);
                        return ($"snapshot round trip with {Twin.IntegratorName(k)}{(stream ? " through a stream" : string.Empty)}", t =>
                        {
                            // The first twin's snapshot restored into the twin itself and into the clean twin: both are
                            // already in that state, so nothing may change.
                            if (ReferenceEquals(t, _a))
                            {
                                SnapshotRoundTrips++;
                            }

                            var snapshot = SimulationSnapshot.Capture(_a.World, _a.Integrators[k]);
                            if (stream)
                            {
                                var bytes = new MemoryStream();
                                snapshot.WriteTo(bytes);
                                bytes.Position = 0;
                                snapshot = SimulationSnapshot.ReadFrom(bytes);
                            }

                            snapshot.RestoreTo(t.World, t.Integrators[k]);
                        }
                        );
                    }

                case < 73:
                    {
                        // One setting per call: each is checked on its own, and a rejected one changes nothing.
                        var (which, tolerance, iterations, flag) = (r.Next(4), r.Value(1e-9, 1e-2), r.Next(-1, 250), r.Chance(0.7));
                        return ($"retune implicit #{which} tol={G(tolerance)} it={iterations} flag={flag}", t =>
                        {
                            var implicitEuler = (ImplicitEuler)t.Integrators[2];
                            switch (which)
                            {
                                case 0:
                                    implicitEuler.Tolerance = tolerance;
                                    break;
                                case 1:
                                    implicitEuler.MaxIterations = iterations;
                                    break;
                                case 2:
                                    implicitEuler.WarmStart = flag;
                                    break;
                                default:
                                    implicitEuler.UserForces = flag ? UserForceTreatment.FiniteDifference : UserForceTreatment.Explicit;
                                    break;
                            }
                        }
                        );
                    }

                case < 75:
                    {
                        var (which, tolerance, steps, size) = (r.Next(3), r.Value(1e-12, 1e-4), r.Next(-1, 400), r.Value(0, 0.01));
                        return ($"retune rk45 #{which} tol={G(tolerance)} steps={steps} h={G(size)}", t =>
                        {
                            var rk45 = (DormandPrince45)t.Integrators[6];
                            switch (which)
                            {
                                case 0:
                                    rk45.Tolerance = tolerance;
                                    break;
                                case 1:
                                    rk45.MaxStepsPerCall = steps;
                                    break;
                                default:
                                    rk45.CurrentStepSize = size;
                                    break;
                            }
                        }
                        );
                    }

                case < 76:
                    {
                        var k = r.Pick(2, 3, 6);
                        var length = r.Next(0, 12);
                        var values = new double[length];
                        for (var i = 0; i < length; i++)
                        {
                            values[i] = r.Chance(0.3) ? r.Pick(0.0, 1.0, 2.0) : r.Value(-1, 1);
                        }

                        return ($"read state into {Twin.IntegratorName(k)} ({length} values)", t => ((IStatefulIntegrator)t.Integrators[k]).ReadState(values));
                    }

                case < 79:
                    {
                        var (k, dt, sub, max) = (r.Next(Twin.IntegratorCount), r.Value(0.005, 0.04), r.Chance(0.9) ? r.Next(1, 5) : 0, r.Chance(0.9) ? r.Next(1, 6) : 0);
                        return ($"new driver {Twin.IntegratorName(k)} dt={G(dt)} sub={sub} max={max}", t =>
                            t.Driver = new FixedTimestepDriver(t.World, t.Integrators[k], dt, sub, max));
                    }

                case < 85:
                    {
                        var frame = r.Chance(0.05) ? r.Pick(-0.01, double.NaN, double.PositiveInfinity, 1e300) : r.Between(0, 0.06);
                        return ($"advance {G(frame)}", t => t.Driver.Advance(frame));
                    }

                case < 87:
                    {
                        var linearize = r.Chance(0.5);
                        return ($"jacobian product{(linearize ? " after linearize" : string.Empty)}", t => t.Product(linearize));
                    }

                case < 90:
                    {
                        // Calm the world down (a valid state, the default limit), so that a sequence does not spend the rest
                        // of its operations on a world that diverges at every step.
                        var state = new double[_a.World.Dimension];
                        for (var k = 0; k < state.Length / 2; k++)
                        {
                            state[k] = r.Between(-1, 1);
                        }

                        return ("calm", t =>
                        {
                            for (var i = 0; i < t.World.Count; i++)
                            {
                                t.World.Unpin(i);
                            }

                            t.World.SetState(state);
                            t.World.DivergenceLimit = ParticleWorld.DefaultDivergenceLimit;
                        }
                        );
                    }

                case < 92 when _a.Rods.Count < 6:
                    {
                        var (i, j, length, cable) = (Index(), Index(), r.Value(0.05, 1.5), r.Chance(0.4));
                        return ($"add {(cable ? "cable" : "rod")} {i}-{j} L={G(length)}", t =>
                        {
                            if (cable)
                            {
                                t.Rods.AddCable(i, j, length);
                            }
                            else
                            {
                                t.Rods.AddRod(i, j, length);
                            }
                        }
                        );
                    }

                case < 93 when _a.Rods.Count < 6:
                    {
                        var (i, anchor, length) = (Index(), Vector(-1, 1), r.Value(0.05, 1.5));
                        return ($"add anchored rod {i} {anchor} L={G(length)}", t => t.Rods.AddAnchoredRod(i, anchor, length));
                    }

                case < 95:
                    {
                        var c = r.Next(4);
                        return ($"toggle constraints {c}", t => t.ToggleConstraints(c));
                    }

                case < 97:
                    {
                        // Sometimes to where the particle is (velocity 0 at any duration), sometimes in an extreme duration.
                        var (i, target, duration, stay) = (r.Chance(0.7) ? PinnedIndex() : Index(), Vector(-1, 1), Duration(), r.Chance(0.5));
                        return ($"move kinematic {i} {(stay ? "where it is" : target.ToString())} in {G(duration)}", t =>
                            t.World.MoveKinematic(i, stay && i >= 0 && i < t.World.Count ? t.World.GetPosition(i) : target, duration));
                    }

                case < 100:
                    {
                        var (i, anchor) = (r.Next(-1, 3), Vector(-1, 1));
                        return ($"move zero-length anchor {i} {anchor}", t => t.Zero.SetAnchor(i, anchor));
                    }

                case < 102:
                    {
                        var (i, radius) = (Index(), r.Value(0.0, 0.4));
                        return ($"set radius {i} {G(radius)}", t => t.World.SetRadius(i, radius));
                    }

                case < 103:
                    {
                        var on = r.Chance(0.5);
                        return ($"particle collisions {on}", t => t.Contacts.ParticleCollisions = on);
                    }

                case < 104:
                    {
                        var (k, restitution, friction) = (r.Next(2), r.Value(0, 1), r.Value(0, 1));
                        return ($"obstacle {k} e={G(restitution)} mu={G(friction)}", t =>
                        {
                            var obstacle = t.Obstacles[k];
                            var (e0, mu0) = (obstacle.Restitution, obstacle.Friction);
                            obstacle.Restitution = restitution;
                            try
                            {
                                obstacle.Friction = friction;
                            }
                            catch (ArgumentException)
                            {
                                obstacle.Restitution = e0; // the pair of settings is all or nothing
                                obstacle.Friction = mu0;
                                throw;
                            }
                        }
                        );
                    }

                case < 105:
                    {
                        var k = r.Next(2);
                        return ($"toggle obstacle {k}", t => t.ToggleObstacle(k));
                    }

                case < 107:
                    {
                        // A constraint set (in the world once toggled in) that throws or writes NaN or infinity from
                        // Resolve, Project or SolveVelocities: the first twin's only, as for the faulty forces.
                        var (fault, after, particle) = (r.Pick(Fault.Throw, Fault.NaN, Fault.Infinity), r.Next(0, 6), r.Next(0, 6));
                        return ($"arm constraints {fault} after {after} at {particle}", t =>
                        {
                            if (ReferenceEquals(t, _a))
                            {
                                t.FaultyConstraints.Arm(fault, after, particle);
                            }
                        }
                        );
                    }

                case < 111:
                    {
                        // Issue 27, item 1: a step of the world (or a frame of its driver) started from inside its own
                        // step, by a force, the contacts' pair filter or a constraint set: armed on the first twin only,
                        // like a fault. Refused, the outer step must fail whole, and its retry equal the clean twin's.
                        var (site, after, frame, k, dt) = (r.Pick(NestingSite.Force, NestingSite.PairFilter, NestingSite.Constraints), r.Next(0, 4), r.Chance(0.3), r.Next(Twin.IntegratorCount), r.Between(1e-4, 0.01));
                        var what = frame ? $"driver frame of {G(dt)}" : $"step {Twin.IntegratorName(k)} dt={G(dt)}";
                        return ($"arm nested {what} from the {site} after {after}", t =>
                        {
                            if (ReferenceEquals(t, _a))
                            {
                                t.Nesting.Arm(site, after, frame ? () => t.Driver.Advance(dt) : () => t.World.Step(t.Integrators[k], dt));
                            }
                        }
                        );
                    }

                case < 115:
                    {
                        // Attaching a particle the body holds already attaches it again (a "calm" may have unpinned it):
                        // Detach changes nothing unless the index is attached, and then Attach succeeds.
                        var i = Index();
                        if (!r.Chance(0.8))
                        {
                            return ($"detach {i}", t => t.Body.Detach(i));
                        }

                        return ($"(re)attach {i}", t =>
                        {
                            _ = t.Body.Detach(i);
                            t.Body.Attach(i);
                        }
                        );
                    }

                case < 119:
                    {
                        // Issue 27, item 2: a pose whose velocities overflow for some particles and not others, or a
                        // duration so short that 1 / duration overflows.
                        var position = r.Chance(0.3) ? new Vector3d(r.Pick(1e-300, 1e300, -1e300, 0.0), 0, 0) : Clean(-1, 1);
                        var orientation = r.Pick(
                            Rotation3d.Identity,
                            Rotation3d.FromAxisAngle(new Vector3d(0, 0, 1), Math.PI),
                            Rotation3d.FromAxisAngle(new Vector3d(1, 1, 0), r.Between(-3, 3)));
                        var duration = Duration();
                        return ($"move body to {position} {orientation.X:R},{orientation.Y:R},{orientation.Z:R},{orientation.W:R} in {G(duration)}", t => t.Body.MoveTo(position, orientation, duration));
                    }

                case < 120:
                    {
                        // Issue 27, item 5: at rest on a plane tilted theta from level, a particle sticks exactly when
                        // tan(theta) <= mu, under every integrator; above, it slides straight down the slope.
                        var (k, degrees, sticks, margin, dt, radius, azimuth, point) = (r.Next(IntegratorCatalog.Names.Count), r.Between(5, 60), r.Chance(0.7), r.Between(0.02, 0.9), r.Between(1e-3, 1.0 / 30.0), r.Chance(0.5) ? 0.0 : r.Between(0.001, 0.2), r.Between(0, 2 * Math.PI), Clean(-2, 2));
                        var name = IntegratorCatalog.Names[k];
                        return ($"probe incline {name} theta={G(degrees)} {(sticks ? "sticks" : "slides")} margin={G(margin)} dt={G(dt)} r={G(radius)} azimuth={G(azimuth)} at {point}", t =>
                        {
                            if (ReferenceEquals(t, _a))
                            {
                                ProbeIncline(name, degrees, sticks, margin, dt, radius, azimuth, point);
                            }
                        }
                        );
                    }

                case < 121:
                    {
                        // Issue 27, item 6: a thin box or a small sphere moving at 1 to 1e4 m/s into a particle at rest
                        // never passes through it (xpbd half of the time, with 1 to 20 substeps).
                        var (xpbd, k, sphere, speed, direction, size, radius, restitution, dt, substeps, lead, offset) = (r.Chance(0.5), r.Next(IntegratorCatalog.Names.Count), r.Chance(0.4), Math.Pow(10, r.Between(0, 4)), Clean(-1, 1), r.Between(1e-4, 0.05), r.Between(0.001, 0.05), r.Chance(0.5) ? 0.0 : r.Between(0, 1), r.Between(1e-3, 1.0 / 30.0), r.Next(1, 21), r.Between(0.2, 10), r.Between(0, 0.5));
                        var name = xpbd ? "xpbd" : IntegratorCatalog.Names[k];
                        return ($"probe moving {(sphere ? "sphere" : "box")} {name} ({substeps} substeps) v={G(speed)} along {direction} size={G(size)} r={G(radius)} e={G(restitution)} dt={G(dt)} lead={G(lead)} offset={G(offset)}", t =>
                        {
                            if (ReferenceEquals(t, _a))
                            {
                                ProbeMovingObstacle(name, substeps, sphere, speed, direction, size, radius, restitution, dt, lead, offset);
                            }
                        }
                        );
                    }

                case < 122 when r.Chance(0.3):
                    {
                        // Issue 27, item 8: 2 to 100 particles spawned at one point above the ground separate: after two
                        // seconds nothing is coincident and no pair overlaps by 1 % of the radius.
                        var (k, count, radius, height, mu, dt, point) = (r.Next(IntegratorCatalog.Names.Count), r.Next(2, 101), r.Between(0.005, 0.05), r.Between(0, 0.3), r.Pick(0.0, 0.5), r.Between(1.0 / 60.0, 1.0 / 30.0), Clean(-1, 1));
                        var name = IntegratorCatalog.Names[k];
                        return ($"probe {count} coincident {name} r={G(radius)} height={G(height)} mu={G(mu)} dt={G(dt)} at {point}", t =>
                        {
                            if (ReferenceEquals(t, _a))
                            {
                                ProbeCoincidentSpawn(name, count, radius, height, mu, dt, point);
                            }
                        }
                        );
                    }

                default:
                    {
                        var (i, anchor) = (r.Next(-1, 3), Vector(-1, 1));
                        return ($"move zero-length anchor {i} {anchor}", t => t.Zero.SetAnchor(i, anchor));
                    }
            }
        }

        /// <summary>A kinematic move's duration: usually a frame's, sometimes one whose inverse overflows, or an invalid one.</summary>
        private double Duration()
        {
            var roll = _random.NextDouble();
            var duration = roll < 0.25 ? _random.Pick(double.Epsilon, 1e-308, 1e-320)
                : roll < 0.35 ? _random.Pick(1e-300, 5.6e-309, 0.0, -0.01, double.NaN, double.PositiveInfinity)
                : _random.Value(0.005, 0.1);
            _tinyDuration = duration > 0.0 && double.IsInfinity(1.0 / duration);
            return duration;
        }

        /// <summary>
        /// A particle at rest on a plane tilted <paramref name="degrees"/> from level (its normal turned towards
        /// <paramref name="azimuth"/>), under gravity, with mu above tan(theta) by the factor 1 + margin or below it by
        /// 1 - margin: it must stay exactly where it is, or slide along the line of steepest descent, on the plane, by
        /// g (sin - mu cos) T^2 / 2 under every force-based integrator (the resting stage makes the tangential motion
        /// exact for constant forces; xpbd's contacts are first order in the substep).
        /// </summary>
        private void ProbeIncline(string integrator, double degrees, bool sticks, double margin, double dt, double radius, double azimuth, Vector3d point)
        {
            Probes++;
            var theta = degrees * Math.PI / 180;
            var normal = new Vector3d(Math.Sin(theta) * Math.Cos(azimuth), Math.Cos(theta), Math.Sin(theta) * Math.Sin(azimuth));
            var mu = Math.Tan(theta) * (sticks ? 1 + margin : 1 - margin);
            var world = new ParticleWorld();
            var start = point + (radius * normal);
            world.AddParticle(start, 1);
            world.SetRadius(0, radius);
            world.AddForce(new Gravity());
            var contacts = new ContactSet();
            contacts.Add(new PlaneObstacle(point, normal, 0, mu));
            world.AddConstraints(contacts);
            var stepper = IntegratorCatalog.Create(integrator);
            var steps = Math.Min(60, (int)Math.Ceiling(0.5 / dt));
            for (var step = 0; step < steps; step++)
            {
                world.Step(stepper, dt);
            }

            var moved = world.GetPosition(0) - start;
            var what = $"incline probe: {integrator}, {degrees} degrees, mu {mu}, dt {dt}, {steps} steps";
            if (sticks)
            {
                Expect(moved.Length < 1e-9 && world.GetVelocity(0).Length < 1e-9, $"{what}: held by static friction, it moved {moved.Length} m and moves at {world.GetVelocity(0)}");
                return;
            }

            var g = new Vector3d(0, -Gravity.StandardAcceleration, 0);
            var slope = g - (Vector3d.Dot(g, normal) * normal);
            var down = slope / slope.Length;
            var distance = Vector3d.Dot(moved, down);
            Expect(distance > 0 && (moved - (distance * down)).Length < 1e-9 * (1 + distance), $"{what}: it slid {moved}, not down the slope {down}");
            if (!IntegratorCatalog.IsPositionBased(integrator))
            {
                var time = steps * dt;
                var exact = 0.5 * Gravity.StandardAcceleration * (Math.Sin(theta) - (mu * Math.Cos(theta))) * time * time;
                Expect(Math.Abs(distance - exact) < 1e-9 * (1 + exact), $"{what}: it slid {distance} m, exactly {exact} m");
            }
        }

        /// <summary>
        /// A thin box (half thickness <paramref name="size"/>, its face 2 m wide, hit <paramref name="offset"/> off its
        /// middle) or a sphere of radius <paramref name="size"/> (hit head on), moving at <paramref name="speed"/> along
        /// <paramref name="direction"/>, meets a particle at rest after about <paramref name="lead"/> steps. At the end of
        /// every step the particle must be outside the obstacle (1e-6 m); in front of the box's face; and behind the
        /// sphere's centre only beside it, never in its shadow (it may slip round a sphere, never through it).
        /// </summary>
        private void ProbeMovingObstacle(
            string integrator, int substeps, bool sphere, double speed, Vector3d direction, double size, double radius, double restitution, double dt, double lead, double offset)
        {
            Probes++;
            var along = direction.Length > 0.1 ? direction / direction.Length : new Vector3d(1, 0, 0);
            var helper = Math.Abs(along.X) < 0.9 ? new Vector3d(1, 0, 0) : new Vector3d(0, 1, 0);
            var side = Vector3d.Cross(along, helper);
            side /= side.Length;
            var start = -(size + radius + (speed * dt * lead)) * along;
            Obstacle obstacle;
            if (sphere)
            {
                obstacle = new SphereObstacle(start, size, restitution);
            }
            else
            {
                var box = new BoxObstacle(start + (offset * side), new Vector3d(size, 1, 1), restitution);
                box.SetOrientation(along, side);
                obstacle = box;
            }

            obstacle.Velocity = speed * along;
            var world = new ParticleWorld();
            world.AddParticle(Vector3d.Zero, 1);
            world.SetRadius(0, radius);
            var contacts = new ContactSet();
            contacts.Add(obstacle);
            world.AddConstraints(contacts);
            var stepper = integrator == "xpbd" ? new Xpbd(substeps) : IntegratorCatalog.Create(integrator);
            var steps = (int)Math.Ceiling(lead) + 5;
            for (var step = 1; step <= steps; step++)
            {
                world.Step(stepper, dt);
                var p = world.GetPosition(0);
                var travel = obstacle.Velocity * world.Time;
                var centre = obstacle.ShapeAt(world.Time).Center;
                var tolerance = 1e-6 + (1e-12 * (speed * world.Time));
                var what = $"moving-obstacle probe, step {step}: the particle at {p}, the {(sphere ? "sphere" : "box")}'s centre at {centre}";
                Expect(obstacle.SignedDistance(p - travel, out _) - radius >= -tolerance, $"{what}: inside");
                var ahead = Vector3d.Dot(p - centre, along);
                if (!sphere)
                {
                    Expect(ahead >= size + radius - tolerance, $"{what}: behind the face");
                }
                else if (ahead < 0)
                {
                    Expect((p - centre - (ahead * along)).Length >= size + radius - tolerance, $"{what}: through the sphere");
                }
            }
        }

        /// <summary>
        /// <paramref name="count"/> particles of radius <paramref name="radius"/> spawned at one point
        /// <paramref name="height"/> above touching the ground, with friction <paramref name="mu"/> on the ground and
        /// between them: after two seconds none is coincident with another, no pair overlaps by 1 % of the radius (and a
        /// few g h^2 more under xpbd), and none is in the ground.
        /// </summary>
        private void ProbeCoincidentSpawn(string integrator, int count, double radius, double height, double mu, double dt, Vector3d point)
        {
            Probes++;
            var world = new ParticleWorld();
            for (var i = 0; i < count; i++)
            {
                world.AddParticle(new Vector3d(point.X, radius + height, point.Z), 1);
                world.SetRadius(i, radius);
            }

            world.AddForce(new Gravity());
            var contacts = new ContactSet { ParticleCollisions = true, ParticleFriction = mu };
            contacts.Add(PlaneObstacle.Ground(0, mu));
            world.AddConstraints(contacts);
            var stepper = IntegratorCatalog.Create(integrator);
            var steps = (int)Math.Ceiling(2.0 / dt); // settled by then (a heap of 67 at 43 Hz: 1.5 s)
            for (var step = 0; step < steps; step++)
            {
                world.Step(stepper, dt);
            }

            var worst = 0.0;
            for (var i = 0; i < count; i++)
            {
                Expect(world.GetPosition(i).Y >= radius - 1e-6, $"coincident probe: particle {i} in the ground at {world.GetPosition(i)}");
                for (var j = i + 1; j < count; j++)
                {
                    var distance = (world.GetPosition(i) - world.GetPosition(j)).Length;
                    Expect(distance > 0, $"coincident probe: particles {i} and {j} still at one point, {world.GetPosition(i)}");
                    worst = Math.Max(worst, (2 * radius) - distance);
                }
            }

            // xpbd projects each contact once per substep of h, and a resting stack sinks by g h^2 per layer in each
            // substep's prediction: its overlaps are a few g h^2 (a heap of 19 of 6 mm at 32 Hz: 3.2 % of the radius with
            // 10 substeps, 0.7 % with 20, none with 40). Particles left on one point overlap by the whole 2 r.
            var h = dt / Xpbd.DefaultSubsteps;
            var allowed = (0.01 * radius) + (integrator == "xpbd" ? 10 * Gravity.StandardAcceleration * h * h : 0.0);
            Expect(worst < allowed, $"coincident probe: after {steps} steps a pair overlaps by {worst / radius:P2} of the radius");
        }

        private Twin Other(Twin t) => ReferenceEquals(t, _a) ? _b : _a;

        private static string G(double value) => value.ToString("R", CultureInfo.InvariantCulture);
    }

    /// <summary>One world with its forces, integrators and driver.</summary>
    private sealed class Twin
    {
        public const int GeneratorCount = 7;
        public const int IntegratorCount = 8;

        private static readonly string[] _integratorNames =
        {
            "explicit-euler", "semi-implicit-euler", "implicit-euler", "implicit-euler (fd)", "rk4", "velocity-verlet", "rk45", "xpbd",
        };

        private readonly IForceGenerator[] _generators;
        private readonly IConstraintSet[] _constraints;

        public Twin(List<(Vector3d Position, Vector3d Velocity, double Mass)> particles)
        {
            foreach (var (p, v, m) in particles)
            {
                World.AddParticle(p, v, m);
            }

            Springs = new SpringNetwork(World);
            Zero = new ZeroLengthSprings(World);
            Dampers = new Dampers(World);
            Zero.AddAnchored(0, new Vector3d(0, 1, 0), 2);
            _generators = new IForceGenerator[] { new Gravity(), new LinearDrag(0.05), Springs, Zero, Dampers, Faulty, FaultyJacobian };
            World.AddForce(_generators[0]);
            World.AddForce(_generators[1]);
            World.AddForce(Springs);
            World.AddForce(Faulty);
            Integrators = new IIntegrator[]
            {
                new ExplicitEuler(),
                new SemiImplicitEuler(),
                new ImplicitEuler(),
                new ImplicitEuler { UserForces = UserForceTreatment.FiniteDifference },
                new RungeKutta4(),
                new VelocityVerlet(),
                new DormandPrince45 { MaxStepsPerCall = 100 },
                new Xpbd(4),
            };
            Rods = new RodNetwork(World);
            Projection = new SpringProjection(Springs);
            Obstacles = new Obstacle[] { new PlaneObstacle(new Vector3d(0, -1, 0), new Vector3d(0, 1, 0), 0.5, 0.3), new SphereObstacle(new Vector3d(0, -0.6, 0), 0.3, 0.2) };
            Contacts = new ContactSet();
            Contacts.Add(Obstacles[0]);
            _constraints = new IConstraintSet[] { Rods, Projection, Contacts, FaultyConstraints };
            Driver = new FixedTimestepDriver(World, Integrators[4], 0.005, 2);

            // Always there in both twins, doing nothing unless the first twin's nesting is armed (a filter that lets
            // every pair collide is the same as none).
            World.AddForce(new NestingForce(Nesting));
            Contacts.PairFilter = new NestingFilter(Nesting);
            FaultyConstraints.Nesting = Nesting;
            Body = new KinematicBody(World, Vector3d.Zero, Rotation3d.Identity);
        }

        public ParticleWorld World { get; } = new();

        public SpringNetwork Springs { get; }

        public ZeroLengthSprings Zero { get; }

        public Dampers Dampers { get; }

        public RodNetwork Rods { get; }

        public SpringProjection Projection { get; }

        public ContactSet Contacts { get; }

        public Obstacle[] Obstacles { get; }

        public FaultyForce Faulty { get; } = new();

        public FaultyJacobianDrag FaultyJacobian { get; } = new();

        public FaultyConstraintSet FaultyConstraints { get; } = new();

        public Nesting Nesting { get; } = new();

        public KinematicBody Body { get; }

        public IIntegrator[] Integrators { get; }

        public FixedTimestepDriver Driver { get; set; }

        public bool IsArmed => Faulty.Armed != Fault.None || FaultyJacobian.Armed || FaultyConstraints.Armed != Fault.None || Nesting.Armed;

        public static string IntegratorName(int k) => _integratorNames[k];

        public void Arm(Fault fault, int after, int particle, bool jacobian)
        {
            if (jacobian)
            {
                FaultyJacobian.Arm(after);
                return;
            }

            Faulty.Particle = particle;
            Faulty.Arm(fault, after);
        }

        public void Disarm()
        {
            Faulty.Arm(Fault.None);
            FaultyJacobian.Armed = false;
            FaultyConstraints.Arm(Fault.None, 0, 0);
            Nesting.Disarm();
        }

        public void Toggle(int g)
        {
            if (!World.RemoveForce(_generators[g]))
            {
                World.AddForce(_generators[g]);
            }
        }

        public void AddAgain(int g, Twin owner) => World.AddForce(owner._generators[g]);

        public void ToggleObstacle(int k)
        {
            if (!Contacts.Remove(Obstacles[k]))
            {
                Contacts.Add(Obstacles[k]);
            }
        }

        public void ToggleConstraints(int c)
        {
            if (!World.RemoveConstraints(_constraints[c]))
            {
                World.AddConstraints(_constraints[c]);
            }
        }

        public void Product(bool linearize)
        {
            ILinearizableSystem system = World;
            var n = World.CoordinateCount;
            if (linearize)
            {
                system.Linearize(World.Time, World.Positions, World.Velocities, 1e-4, 1e-2, UserForceTreatment.Explicit, new double[n]);
            }

            system.AddJacobianProduct(new double[n], new double[n]);
        }

        /// <summary>What a failed call must restore: the world (a snapshot) and every integrator's state.</summary>
        public (SimulationSnapshot World, double[][] Integrators) Save()
        {
            var states = new double[IntegratorCount][];
            for (var k = 0; k < IntegratorCount; k++)
            {
                if (Integrators[k] is IStatefulIntegrator stateful)
                {
                    states[k] = new double[stateful.StateLength];
                    stateful.WriteState(states[k]);
                }
            }

            return (SimulationSnapshot.Capture(World), states);
        }

        public void Restore((SimulationSnapshot World, double[][] Integrators) saved)
        {
            saved.World.RestoreTo(World);
            for (var k = 0; k < IntegratorCount; k++)
            {
                if (Integrators[k] is IStatefulIntegrator stateful)
                {
                    stateful.ReadState(saved.Integrators[k]);
                }
            }
        }

        /// <summary>Which parts of <see cref="Observe()"/> differ between two twins, for a failure's message.</summary>
        public static string Difference(Twin a, Twin b)
        {
            var differing = new List<string>();
            for (var part = 0; part < Parts; part++)
            {
                if (!a.Observe(part).AsSpan().SequenceEqual(b.Observe(part)))
                {
                    differing.Add(part < FirstIntegratorPart ? _partNames[part] : $"{_integratorNames[part - FirstIntegratorPart]}'s state");
                }
            }

            if (!a.Observe(8).AsSpan().SequenceEqual(b.Observe(8)))
            {
                differing.Add($"(first: {a.Logs()}; second: {b.Logs()})");
            }

            return string.Join(", ", differing);
        }

        private string Logs() => string.Format(
            CultureInfo.InvariantCulture,
            "radii [{0}], {1} impacts [{2}], {3} pairs, tensions [{4}]",
            string.Join(" ", World.Radii.ToArray()),
            Contacts.ImpactCount,
            string.Join(" ", Contacts.Impacts.ToArray().Select(i => $"{i.Time:R}/{i.Particle}/{i.Other}/{i.WithObstacle}/{i.NormalSpeed:R}/{i.Resting}")),
            Contacts.CandidatePairCount,
            string.Join(" ", Enumerable.Range(0, Rods.Count).Select(Rods.GetTension)));

        private const int FirstIntegratorPart = 9;
        private const int Parts = FirstIntegratorPart + IntegratorCount;

        private static readonly string[] _partNames = { "count, time, limit", "state", "masses", "inverse masses", "pins", "forces", "element counts", "driver", "radii, contacts, rods and body" };

        /// <summary>Everything a call may change, as bytes: world, forces, constraints, integrator states, driver, rendering.</summary>
        public Observation Observe() => new(Observe(-1));

        /// <summary>The bytes of part <paramref name="only"/> of what a call may change, or of every part (-1).</summary>
        private byte[] Observe(int only)
        {
            using var bytes = new MemoryStream();
            using (var w = new BinaryWriter(bytes))
            {
                bool Part(int part) => only < 0 || only == part;
                if (Part(0))
                {
                    w.Write(World.Count);
                    w.Write(World.Time);
                    w.Write(World.DivergenceLimit);
                }

                if (Part(1))
                {
                    foreach (var v in World.State)
                    {
                        w.Write(v);
                    }
                }

                if (Part(2))
                {
                    foreach (var m in World.Masses)
                    {
                        w.Write(m);
                    }
                }

                if (Part(3))
                {
                    foreach (var m in World.InverseMasses)
                    {
                        w.Write(m);
                    }
                }

                for (var i = 0; i < World.Count && Part(4); i++)
                {
                    w.Write(World.IsPinned(i));
                }

                if (Part(5))
                {
                    foreach (var g in World.Forces)
                    {
                        w.Write(Array.IndexOf(_generators, g));
                    }
                }

                if (Part(6))
                {
                    w.Write(Springs.Count);
                    w.Write(Springs.AnchoredCount);
                    w.Write(Zero.Count);
                    w.Write(Dampers.Count);
                    w.Write(Rods.Count);
                    foreach (var c in World.Constraints)
                    {
                        w.Write(Array.IndexOf(_constraints, c));
                    }
                }

                if (Part(7))
                {
                    w.Write(Driver.Accumulator);
                    w.Write(Driver.StepCount);
                    w.Write(Driver.LastDroppedTime);
                    w.Write(Driver.TotalDroppedTime);
                    var vertices = new Vector3[World.Count];
                    try
                    {
                        Driver.InterpolatePositions(vertices);
                    }
                    catch (InvalidOperationException)
                    {
                        // The world grew after the driver was made: nothing to render.
                    }

                    foreach (var vertex in vertices)
                    {
                        w.Write(vertex.X);
                        w.Write(vertex.Y);
                        w.Write(vertex.Z);
                    }
                }

                if (Part(8))
                {
                    foreach (var radius in World.Radii)
                    {
                        w.Write(radius);
                    }

                    w.Write(Contacts.ParticleCollisions);
                    w.Write(Contacts.Obstacles.Count);
                    foreach (var obstacle in Obstacles)
                    {
                        w.Write(System.Linq.Enumerable.Contains(Contacts.Obstacles, obstacle));
                        w.Write(obstacle.Restitution);
                        w.Write(obstacle.Friction);
                    }

                    w.Write(Contacts.ImpactCount);
                    w.Write(Contacts.CandidatePairCount);
                    foreach (var impact in Contacts.Impacts)
                    {
                        w.Write(impact.Time);
                        w.Write(impact.Particle);
                        w.Write(impact.Other);
                        w.Write(impact.WithObstacle);
                        w.Write(impact.NormalSpeed);
                        w.Write(impact.Resting);
                    }

                    for (var link = 0; link < Rods.Count; link++)
                    {
                        w.Write(Rods.GetTension(link));
                    }

                    w.Write(Body.Position.X);
                    w.Write(Body.Position.Y);
                    w.Write(Body.Position.Z);
                    w.Write(Body.Orientation.X);
                    w.Write(Body.Orientation.Y);
                    w.Write(Body.Orientation.Z);
                    w.Write(Body.Orientation.W);
                    foreach (var particle in Body.Particles)
                    {
                        w.Write(particle);
                    }
                }

                for (var k = 0; k < IntegratorCount; k++)
                {
                    if (Part(FirstIntegratorPart + k) && Integrators[k] is IStatefulIntegrator stateful)
                    {
                        var state = new double[stateful.StateLength];
                        stateful.WriteState(state);
                        foreach (var v in state)
                        {
                            w.Write(v);
                        }
                    }
                }
            }

            return bytes.ToArray();
        }

        public void CheckInvariants(Action<bool, string> expect)
        {
            expect(double.IsFinite(World.Time), "the time is not finite");
            var state = World.State;
            for (var k = 0; k < state.Length; k++)
            {
                if (!double.IsFinite(state[k]))
                {
                    expect(false, $"state value {k} is {state[k]}");
                }
            }

            for (var i = 0; i < World.Count; i++)
            {
                var m = World.Masses[i];
                var inverse = World.InverseMasses[i];
                expect(m > 0 && double.IsFinite(m) && double.IsFinite(1 / m), $"particle {i} has mass {m}");
                expect(World.IsPinned(i) ? inverse == 0 : inverse == 1 / m, $"particle {i}'s inverse mass {inverse} does not match its mass {m}");
            }
        }
    }

    /// <summary>
    /// A constraint set that does nothing until armed, then fails as told on its <c>after</c>-th call from the arming
    /// on (Resolve after a force-based step; Project and SolveVelocities in xpbd's substeps).
    /// </summary>
    private sealed class FaultyConstraintSet : IConstraintSet
    {
        private int _after;
        private int _particle;
        private int _calls;

        public Fault Armed { get; private set; }

        public void Arm(Fault fault, int after, int particle)
        {
            Armed = fault;
            _after = after;
            _particle = particle;
            _calls = 0;
        }

        public void Resolve(in ConstraintContext context) => Call(context.Positions, context.Velocities);

        public void Project(in ConstraintContext context) => Call(context.Positions, context.Velocities);

        public void SolveVelocities(in ConstraintContext context) => Call(context.Positions, context.Velocities);

        public Nesting? Nesting { get; set; }

        private void Call(Span<double> positions, Span<double> velocities)
        {
            Nesting?.Call(NestingSite.Constraints);
            if (Armed == Fault.None || _calls++ < _after || 3 * _particle >= positions.Length)
            {
                return;
            }

            switch (Armed)
            {
                case Fault.Throw:
                    throw new InvalidOperationException("FaultyConstraintSet: armed to throw.");
                case Fault.NaN:
                    velocities[(3 * _particle) + 1] = double.NaN;
                    break;
                case Fault.Infinity:
                    positions[3 * _particle] = double.PositiveInfinity;
                    break;
            }
        }
    }

    /// <summary>Where an armed <see cref="Nesting"/> calls the world back from inside its step.</summary>
    private enum NestingSite
    {
        Force,
        PairFilter,
        Constraints,
    }

    /// <summary>
    /// A call into the world (a nested step, a driver frame) that the first twin's force, pair filter or constraint set
    /// makes from inside the world's step once armed: on its <c>after</c>-th call from the arming on, once.
    /// </summary>
    private sealed class Nesting
    {
        private NestingSite _site;
        private int _after;
        private Action? _action;

        public bool Armed => _action is not null;

        public void Arm(NestingSite site, int after, Action action)
        {
            (_site, _after, _action) = (site, after, action);
        }

        public void Disarm() => _action = null;

        public void Call(NestingSite site)
        {
            if (_action is null || site != _site || _after-- > 0)
            {
                return;
            }

            var action = _action;
            _action = null;
            action();
        }
    }

    private sealed class NestingForce : IForceGenerator
    {
        private readonly Nesting _nesting;

        public NestingForce(Nesting nesting)
        {
            _nesting = nesting;
        }

        public void AddForces(in ParticleState state, Span<double> forces) => _nesting.Call(NestingSite.Force);
    }

    private sealed class NestingFilter : IContactPairFilter
    {
        private readonly Nesting _nesting;

        public NestingFilter(Nesting nesting)
        {
            _nesting = nesting;
        }

        public bool MayCollide(int first, int second)
        {
            _nesting.Call(NestingSite.PairFilter);
            return true;
        }
    }
}
