// The Mono comparison program: the same source, compiled by Mono's mcs and run on Mono, and compiled by the .NET SDK
// (RuntimeComparison.csproj) and run on CoreCLR, against the same netstandard2.1 ParticlePhysics.dll. It prints one
// line per result, "hash <case> <FNV-1a of the raw bits>" and "count <case> ..." (solver iterations), which .ci/mono
// requires to be equal on both runtimes, and "time <case> <wall> <cpu> <unit>", of which .ci/mono prints the
// Mono / CoreCLR ratios. See README.md beside it.
//
// C# 7.2 at most (mcs -langversion:7.2): no nullable annotations, no file-scoped namespace, no switch expressions.
// Hashes read the bits of the doubles and floats, never their text: "R" formatting differs between the runtimes.
using System;
using System.Collections.Generic;
using System.Diagnostics;
using System.Globalization;
using System.IO;
using System.Runtime.InteropServices;
using ParticlePhysics.Bodies;
using ParticlePhysics.Cloth;
using ParticlePhysics.Constraints;
using ParticlePhysics.Contacts;
using ParticlePhysics.Driver;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Parallel;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Scenes;
using ParticlePhysics.Scenes.Meshes;
using ParticlePhysics.Snapshots;
using UnityEngine.StandIn;

namespace ParticlePhysics.RuntimeComparison
{
    /// <summary>Runs every comparison case, then the timings, and prints their results.</summary>
    internal static class Program
    {
        /// <summary>The sizes (particles per side) of the sample's per-frame timings, up to the Inspector's largest.</summary>
        private static readonly int[] _frameSizes = { 8, 16, 21, 32, 48, 64 };

        private static int Main(string[] args)
        {
            var timings = args.Length == 0 || Array.IndexOf(args, "--timings") >= 0;
            var hashes = args.Length == 0 || Array.IndexOf(args, "--hashes") >= 0;
            if (!timings && !hashes)
            {
                Console.Error.WriteLine("usage: RuntimeComparison [--hashes] [--timings] (default: both)");
                return 2;
            }

            Console.WriteLine("runtime " + RuntimeDescription());
            if (hashes)
            {
                EveryIntegrator();
                DivergingRungeKutta4();
                FixedTimestepDriverWithInterpolation();
                Snapshots("implicit-euler");
                Snapshots("rk45");
                ParallelRunner();
                RunnerHandOffs();
                UnitySample();
                Constraints();
                Scenes();
                Bodies();
            }

            if (timings)
            {
                TimeRungeKutta4Step();
                TimeImplicitEulerSecond();
                TimeSampleFrames();
            }

            return 0;
        }

        // Rigid and soft bodies (issue "solids from particles"): a box spun about its intermediate axis (its own
        // trigonometry and rotation extraction), and rigid and soft boxes heaped on the ground through the contact set.
        private static void Bodies()
        {
            var world = new ParticleWorld();
            var bodies = new ShapeMatching(world);
            AddBox(world, bodies, new Vector3d(0, 0, 0), new Vector3d(0.8, 0.4, 0.2), Rotation3d.Identity, 0.0);
            world.AddConstraints(bodies);
            bodies.SetMotion(0, Vector3d.Zero, new Vector3d(0.01, 3, 0.01));
            var xpbd = new Xpbd(10);
            for (var step = 0; step < 240; step++)
            {
                world.Step(xpbd, 1.0 / 120);
            }

            var hash = new BitHash();
            hash.Add(world.Positions.ToArray());
            hash.Add(world.Velocities.ToArray());
            var pose = bodies.GetPose(0);
            hash.Add(pose.Rotation.W);
            hash.Add(pose.Rotation.X);
            hash.Add(pose.AngularVelocity.Y);
            Print("bodies/spin", hash);

            var heap = new ParticleWorld();
            var heaped = new ShapeMatching(heap);
            for (var b = 0; b < 6; b++)
            {
                AddBox(heap, heaped, new Vector3d(0.05 * b, 0.2 + (0.35 * b), 0.03 * b), new Vector3d(0.3, 0.2, 0.2), new Rotation3d(0.1 * b, 0.2, -0.1 * b, 1), b % 2 == 0 ? 0.0 : 0.3);
            }

            heap.AddForce(Gravity.Down(9.81));
            var contacts = new ContactSet();
            contacts.ParticleCollisions = true;
            contacts.ParticleFriction = 0.4;
            contacts.PairFilter = heaped.PairFilter;
            contacts.Add(PlaneObstacle.Ground(0, 0.5));
            contacts.SetParticleMaterial(0, 8, 0.8, 0.2);
            heap.AddConstraints(heaped);
            heap.AddConstraints(contacts);
            var heapStep = new Xpbd(10);
            for (var step = 0; step < 90; step++)
            {
                heap.Step(heapStep, 1.0 / 60);
            }

            hash = new BitHash();
            hash.Add(heap.Positions.ToArray());
            hash.Add(heap.Velocities.ToArray());
            Print("bodies/heap", hash);
            Sleeping();
        }

        // Sleeping (issue "solids from particles"): a heap of boxes and grains that falls asleep, then a ball that
        // wakes part of it; the islands, the wake in the substep of the impact, and what sleeps at the end.
        private static void Sleeping()
        {
            var world = new ParticleWorld();
            world.SleepSpeed = 0.05;
            var bodies = new ShapeMatching(world);
            for (var b = 0; b < 3; b++)
            {
                AddBox(world, bodies, new Vector3d(0.35 * b, 0.15, 0), new Vector3d(0.3, 0.2, 0.2), new Rotation3d(0, 0.1 * b, 0, 1), b == 1 ? 0.3 : 0.0);
            }

            var firstGrain = world.Count;
            for (var i = 0; i < 200; i++)
            {
                var p = world.AddParticle(new Vector3d(0.4 + (0.021 * (i % 5)) + (0.001 * (i % 3)), 0.011 + (0.021 * (i / 25)), 0.3 + (0.021 * ((i / 5) % 5))), 0.004);
                world.SetRadius(p, 0.01);
            }

            world.AddForce(Gravity.Down(9.81));
            var contacts = new ContactSet();
            contacts.ParticleCollisions = true;
            contacts.ParticleFriction = 0.4;
            contacts.PairFilter = bodies.PairFilter;
            contacts.SetGranular(firstGrain, 200, 0.6, 0.3);
            contacts.Add(PlaneObstacle.Ground(0, 0.8));
            world.AddConstraints(bodies);
            world.AddConstraints(contacts);
            var xpbd = new Xpbd(10);
            for (var step = 0; step < 240; step++)
            {
                world.Step(xpbd, 1.0 / 60);
            }

            var asleep = world.SleepingCount;
            var ball = world.AddParticle(new Vector3d(0.0, 0.6, 0.0), new Vector3d(0, -3, 0), 2.0);
            world.SetRadius(ball, 0.05);
            for (var step = 0; step < 60; step++)
            {
                world.Step(xpbd, 1.0 / 60);
            }

            var hash = new BitHash();
            hash.Add(world.Positions.ToArray());
            hash.Add(world.Velocities.ToArray());
            hash.Add(world.InverseMasses.ToArray());
            Print("bodies/sleeping", hash);
            Console.WriteLine("count bodies/sleeping " + asleep + " " + world.SleepingCount);
        }

        private static void AddBox(ParticleWorld world, ShapeMatching bodies, Vector3d centre, Vector3d size, Rotation3d rotation, double softness)
        {
            var points = BodyLattice.Box(centre, size, rotation, 0.1);
            var particles = new int[points.Length];
            for (var k = 0; k < points.Length; k++)
            {
                particles[k] = world.AddParticle(points[k], 1.0 / points.Length);
                world.SetRadius(particles[k], 0.05);
            }

            if (softness > 0.0)
            {
                bodies.AddSoft(particles, 1.0 - softness, rotation);
            }
            else
            {
                bodies.AddRigid(particles, rotation);
            }
        }

        // Every integrator of the catalog on the course's 16 x 16 cloth, 200 steps of 1 ms (stable for all of them):
        // the state, the time and the integrator's own state.
        private static void EveryIntegrator()
        {
            foreach (var name in IntegratorCatalog.Names)
            {
                var world = Cloth(16);
                var integrator = IntegratorCatalog.Create(name);
                for (var step = 0; step < 200; step++)
                {
                    world.Step(integrator, 0.001);
                }

                var hash = new BitHash();
                hash.Add(world.Time);
                hash.Add(world.State);
                AddIntegratorState(hash, integrator);
                Print("integrator/" + name, hash);
            }
        }

        // Rods and cables (issue 12): the pendulum and the hanging chain (band solve) under every integrator, a net of rods
        // (conjugate gradients) under rk4 and xpbd, and a cable hanging from an anchor that a kinematic body drives.
        private static void Constraints()
        {
            foreach (var name in IntegratorCatalog.Names)
            {
                var pendulum = new PendulumScenario { Angle = 120 }.Build();
                var chain = new HangingChainScenario { Particles = 21 }.Build();
                var integrator = IntegratorCatalog.Create(name);
                Run(pendulum, integrator, 0.002, 300);
                Run(chain, IntegratorCatalog.Create(name), 0.002, 300);
                Print("pendulum/" + name, StateHash(pendulum, integrator));
                var hash = new BitHash();
                hash.Add(chain.State);
                Print("hanging-chain/" + name, hash);
            }

            foreach (var name in new[] { "rk4", "xpbd" })
            {
                var net = new ParticleWorld();
                for (var i = 0; i < 144; i++)
                {
                    net.AddParticle(new Vector3d(i % 12 * 0.05, 0, i / 12 * 0.05), 0.01);
                }

                net.Pin(0);
                net.AddForce(new Forces.Gravity());
                var rods = new RodNetwork(net);
                for (var i = 0; i < 144; i++)
                {
                    if (i % 12 + 1 < 12)
                    {
                        rods.AddRod(i, i + 1, 0.05);
                    }

                    if (i + 12 < 144)
                    {
                        rods.AddRod(i, i + 12, 0.05);
                    }
                }

                net.AddConstraints(rods);
                var body = new KinematicBody(net, Vector3d.Zero, Rotation3d.Identity);
                body.Attach(0);
                var cables = new RodNetwork(net);
                var weight = net.AddParticle(new Vector3d(0.3, -0.2, 0.1), 0.2);
                cables.AddCable(0, weight, 0.5);
                net.AddConstraints(cables);
                var integrator = IntegratorCatalog.Create(name);
                for (var frame = 1; frame <= 30; frame++)
                {
                    body.MoveTo(new Vector3d(0.2 * frame / 60.0, 0, 0), Rotation3d.FromAxisAngle(new Vector3d(0, 1, 0), 0.3 * frame / 60.0), 1.0 / 60);
                    Run(net, integrator, 1.0 / 600, 10);
                }

                Print("rod-net/" + name, StateHash(net, integrator));
            }
        }

        // RK4 at one 60 Hz frame per step on the 32 x 32 cloth diverges: where and when it says so, and the last good
        // state it leaves the world in.
        private static void DivergingRungeKutta4()
        {
            var world = Cloth(32);
            var rk4 = new RungeKutta4();
            for (var step = 0; step < 600; step++)
            {
                try
                {
                    world.Step(rk4, 1.0 / 60);
                }
                catch (SimulationDivergedException e)
                {
                    var hash = new BitHash();
                    hash.Add(step);
                    hash.Add(e.Time);
                    hash.Add(e.LastFiniteTime);
                    hash.Add(e.Particle);
                    hash.Add(e.Component);
                    hash.Add(e.Value);
                    hash.Add(e.Limit);
                    hash.Add(world.Time);
                    hash.Add(world.State);
                    Print("rk4-divergence", hash);
                    Console.WriteLine(string.Format(
                        CultureInfo.InvariantCulture, "info rk4-divergence step {0}, particle {1}", step, e.Particle));
                    return;
                }
            }

            throw new InvalidOperationException("RK4 at dt = 1/60 s on the 32 x 32 cloth did not diverge in 600 steps.");
        }

        // The fixed-timestep driver under uneven frame times (and one hitch past MaxStepsPerFrame), with sub-steps: the
        // interpolated float positions of every frame, and the driver's counters.
        private static void FixedTimestepDriverWithInterpolation()
        {
            var cloth = ClothBuilderFor(16).Build();
            var driver = new FixedTimestepDriver(cloth.System, new SemiImplicitEuler(), 1.0 / 60, subSteps: 8);
            var positions = new System.Numerics.Vector3[cloth.ParticleCount];
            var hash = new BitHash();
            for (var frame = 0; frame < 240; frame++)
            {
                var frameTime = frame == 100 ? 0.5 : (frame % 3 == 0 ? 0.021 : 0.013);
                hash.Add(driver.Advance(frameTime));
                hash.Add(driver.InterpolationFactor);
                driver.InterpolatePositions(cloth.FirstParticle, cloth.ParticleCount, positions);
                hash.Add(positions);
            }

            hash.Add(driver.StepCount);
            hash.Add(driver.TotalDroppedTime);
            hash.Add(cloth.System.State);
            Print("driver", hash);
        }

        // Save and restore mid-run, in memory and through a stream into a world built anew: running on after either
        // gives the bits of running on without them. The stream's bytes are compared across runtimes too.
        private static void Snapshots(string integratorName)
        {
            var world = Cloth(16);
            var integrator = IntegratorCatalog.Create(integratorName);
            var dt = integratorName == "implicit-euler" ? 1.0 / 60 : 0.001;
            Run(world, integrator, dt, 30);
            var snapshot = SimulationSnapshot.Capture(world, integrator);
            var stream = new MemoryStream();
            snapshot.WriteTo(stream);

            Run(world, integrator, dt, 30);
            var straight = StateHash(world, integrator);

            snapshot.RestoreTo(world, integrator);
            Run(world, integrator, dt, 30);
            var inMemory = StateHash(world, integrator);

            var rebuilt = Cloth(16);
            var freshIntegrator = IntegratorCatalog.Create(integratorName);
            stream.Position = 0;
            SimulationSnapshot.ReadFrom(stream).RestoreTo(rebuilt, freshIntegrator);
            Run(rebuilt, freshIntegrator, dt, 30);
            var throughStream = StateHash(rebuilt, freshIntegrator);

            Require(inMemory == straight, "snapshot/" + integratorName + ": the run restored in memory differs from the straight run");
            Require(throughStream == straight, "snapshot/" + integratorName + ": the run restored from a stream differs from the straight run");
            Print("snapshot/" + integratorName + "/run", straight);
            var bytes = new BitHash();
            bytes.Add(stream.ToArray());
            Print("snapshot/" + integratorName + "/stream", bytes.Value);
        }

        // WorkerThreadRunner with two threads gives the bits of one thread.
        private static void ParallelRunner()
        {
            var single = Cloth(32);
            var rk4 = new RungeKutta4();
            Run(single, rk4, 0.001, 100);

            var parallel = Cloth(32);
            var parallelRk4 = new RungeKutta4();
            using (var runner = new WorkerThreadRunner(2))
            {
                parallel.Runner = runner;
                Run(parallel, parallelRk4, 0.001, 100);
                parallel.Runner = null;
            }

            var one = StateHash(single, rk4);
            var two = StateHash(parallel, parallelRk4);
            Require(one == two, "parallel: WorkerThreadRunner(2) gives other bits than one thread");
            Print("parallel", two);

            // xpbd on the 32 x 32 cloth (1024 particles: its springs projected in 4 strips of rows, two phases), one
            // thread and two, one second at 60 Hz.
            var xpbdSingle = Cloth(32);
            var xpbd = new Xpbd();
            Run(xpbdSingle, xpbd, 1.0 / 60, 60);
            var xpbdParallel = Cloth(32);
            var parallelXpbd = new Xpbd();
            using (var runner = new WorkerThreadRunner(2))
            {
                xpbdParallel.Runner = runner;
                Run(xpbdParallel, parallelXpbd, 1.0 / 60, 60);
                xpbdParallel.Runner = null;
            }

            var xpbdOne = StateHash(xpbdSingle, xpbd);
            var xpbdTwo = StateHash(xpbdParallel, parallelXpbd);
            Require(xpbdOne == xpbdTwo, "parallel/xpbd: WorkerThreadRunner(2) gives other bits than one thread");
            Print("parallel/xpbd", xpbdTwo);
        }

        // WorkerThreadRunner's hand-off protocol on this runtime (its memory model, Monitor and Stopwatch): 30 000
        // runs of pseudo-random sizes (0 to 63 chunks, mostly a few) with every chunk counted after each run, and
        // 2 000 runs whose chunks wait for each other, so that every worker must wake (a lost wake-up leaves the
        // chunks waiting, and they give up after 10 s); now and then a pause long enough for the workers to go to
        // sleep. On 2, 3 and 4 threads, adaptive and never spinning. The hash is of the sizes run: equal on both
        // runtimes when every check passed.
        private static void RunnerHandOffs()
        {
            var hash = new BitHash();
            var configurations = new[]
            {
                new KeyValuePair<int, TimeSpan>(2, WorkerThreadRunner.DefaultSpinLimit),
                new KeyValuePair<int, TimeSpan>(3, TimeSpan.Zero),
                new KeyValuePair<int, TimeSpan>(4, WorkerThreadRunner.DefaultSpinLimit),
            };
            foreach (var configuration in configurations)
            {
                using (var runner = new WorkerThreadRunner(configuration.Key, configuration.Value))
                {
                    var counted = new CountedWork(64);
                    var seed = 12345u;
                    long chunks = 0;
                    for (var run = 0; run < 30000; run++)
                    {
                        seed = unchecked((seed * 1664525u) + 1013904223u);
                        var chunkCount = (int)(seed >> 26);
                        if ((seed & 0x3000) != 0)
                        {
                            chunkCount &= 7;
                        }

                        counted.Expect(chunkCount);
                        runner.Run(counted, chunkCount);
                        var wrong = counted.CheckAndClear(chunkCount);
                        Require(wrong < 0, "runner-handoffs: run " + run + " of " + chunkCount + " chunks ran chunk " + wrong + " other than once");
                        chunks += chunkCount;
                        if (run % 3000 == 0)
                        {
                            System.Threading.Thread.Sleep(2);
                        }
                    }

                    var meeting = new MeetingWork(configuration.Key);
                    for (var run = 0; run < 2000; run++)
                    {
                        meeting.Reset();
                        runner.Run(meeting, configuration.Key);
                        Require(!meeting.GaveUp, "runner-handoffs: a run that needs every worker never had them all: a lost wake-up");
                        if (run % 500 == 0)
                        {
                            System.Threading.Thread.Sleep(2);
                        }
                    }

                    hash.Add(configuration.Key);
                    hash.Add(chunks);
                }
            }

            Print("runner-handoffs", hash);
        }

        // The Unity sample itself, on the stand-in UnityEngine: 120 frames of the default 21 x 21 cloth, every vertex
        // and normal of the mesh.
        private static void UnitySample()
        {
            var cloth = StartSample(21);
            var hash = new BitHash();
            for (var frame = 0; frame < 120; frame++)
            {
                PlayerLoop.RunFrame(frame % 2 == 0 ? 0.0125f : 0.02f);
                hash.Add(MemoryMarshal.Cast<UnityEngine.Vector3, float>(cloth.MeshVertices()).ToArray());
            }

            hash.Add(MemoryMarshal.Cast<UnityEngine.Vector3, float>(cloth.MeshNormals()).ToArray());
            RequireNoUnityErrors();
            Print("unity-sample", hash);
            PlayerLoop.Reset();
        }

        // One RK4 step of the 64 x 64 cloth at 1 ms: the median of 7 batches of 16 steps from rest, after a warm-up.
        private static void TimeRungeKutta4Step()
        {
            var world = Cloth(64);
            var initial = world.State.ToArray();
            var rk4 = new RungeKutta4();
            const int StepsPerBatch = 16;
            Run(world, rk4, 0.001, 2 * StepsPerBatch);
            var wall = new double[7];
            var cpu = new double[7];
            for (var b = 0; b < wall.Length; b++)
            {
                world.SetState(initial);
                var timer = Timer.Start();
                Run(world, rk4, 0.001, StepsPerBatch);
                wall[b] = timer.WallMilliseconds * 1000 / StepsPerBatch;
                cpu[b] = timer.CpuMilliseconds * 1000 / StepsPerBatch;
            }

            PrintTime("rk4-step-64", Median(wall), Median(cpu), "us");
        }

        // One simulated second of the 64 x 64 cloth under implicit Euler at 60 Hz, from rest (the solver's hardest
        // frames), with the default tolerance 1e-6; a warm-up on another cloth first.
        private static void TimeImplicitEulerSecond()
        {
            Run(Cloth(64), new ImplicitEuler(), 1.0 / 60, 3);
            var world = Cloth(64);
            var implicitEuler = new ImplicitEuler();
            long iterations = 0;
            var timer = Timer.Start();
            for (var step = 0; step < 60; step++)
            {
                world.Step(implicitEuler, 1.0 / 60);
                iterations += implicitEuler.LastIterations;
            }

            PrintTime("implicit-euler-64-second", timer.WallMilliseconds, timer.CpuMilliseconds, "ms");
            PrintIterations("implicit-euler-64-second", iterations, 60);
        }

        // What a frame of the Unity sample costs at each size: its Update (steps, interpolation, normals, the stand-in
        // Mesh's copies), averaged over seconds 1 to 3 of a 60 Hz run from rest (second 0 warms up).
        private static void TimeSampleFrames()
        {
            foreach (var n in _frameSizes)
            {
                var sample = StartSample(n);
                for (var frame = 0; frame < 60; frame++)
                {
                    PlayerLoop.RunFrame(1f / 60);
                }

                const int Frames = 120;
                var solver = (ImplicitEuler)sample.Component.Driver.Integrator;
                long iterations = 0;
                var timer = Timer.Start();
                for (var frame = 0; frame < Frames; frame++)
                {
                    PlayerLoop.RunFrame(1f / 60);
                    iterations += solver.LastIterations;
                }

                var wall = timer.WallMilliseconds / Frames;
                var cpu = timer.CpuMilliseconds / Frames;
                RequireNoUnityErrors();
                PlayerLoop.Reset();
                var name = "sample-frame-" + n.ToString(CultureInfo.InvariantCulture);
                PrintTime(name, wall, cpu, "ms");
                PrintIterations(name, iterations, Frames);
            }
        }

        private static SampleHandle StartSample(int particlesPerSide)
        {
            PlayerLoop.Reset();
            var gameObject = new UnityEngine.GameObject("Cloth");
            var cloth = gameObject.AddComponent<SimulatedCloth>();
            cloth.particlesPerSide = particlesPerSide;
            PlayerLoop.RunFrame(0f);   // Start, then an Update of no time
            return new SampleHandle(gameObject, cloth);
        }

        private static void RequireNoUnityErrors()
        {
            Require(UnityEngine.Debug.Errors.Count == 0, "the Unity sample logged: " + string.Join("\n", UnityEngine.Debug.Errors));
        }

        private static ParticleWorld Cloth(int n) => new ClothScenario { Resolution = 1.0 / (n - 1) }.Build();

        private static ClothBuilder ClothBuilderFor(int n) => new ClothScenario { Resolution = 1.0 / (n - 1) }.CreateBuilder();

        private static void Run(ParticleWorld world, IIntegrator integrator, double dt, int steps)
        {
            for (var step = 0; step < steps; step++)
            {
                world.Step(integrator, dt);
            }
        }

        // Scene files: numbers of 1 to 25 digits at exponents from -300 to 280, written by integer arithmetic (the
        // runtimes format doubles differently), read as particle positions from JSON and as vertices from OBJ, whose
        // bits must agree (Mono's own double.Parse is off by an ulp on some of them); then a sample scene, stepped.
        private static void Scenes()
        {
            var seed = 20261203UL;
            var numbers = new string[3000];
            for (var i = 0; i < numbers.Length; i++)
            {
                numbers[i] = DecimalText(ref seed);
            }

            var json = new System.Text.StringBuilder("{ \"gravity\": [0, 0, 0], \"objects\": [{ \"type\": \"particles\", \"positions\": [");
            var obj = new System.Text.StringBuilder();
            for (var i = 0; i < numbers.Length; i += 3)
            {
                json.Append(i == 0 ? "[" : ", [").Append(numbers[i]).Append(", ").Append(numbers[i + 1]).Append(", ").Append(numbers[i + 2]).Append(']');
                obj.Append("v ").Append(numbers[i]).Append(' ').Append(numbers[i + 1]).Append(' ').Append(numbers[i + 2]).Append('\n');
            }

            json.Append("] }] }");
            obj.Append("f 1 2 3\n");
            var world = Scene.Parse(json.ToString(), "numbers.json").Build();
            var hash = new BitHash();
            hash.Add(world.Positions);
            Print("scene/numbers", hash);

            var path = Path.Combine(Path.GetTempPath(), "pp-runtime-comparison-" + Process.GetCurrentProcess().Id + ".obj");
            try
            {
                File.WriteAllText(path, obj.ToString());
                var mesh = ObjReader.Read(path, "numbers.obj");
                var vertices = new BitHash();
                vertices.Add(mesh.Vertices);
                Print("scene/obj-numbers", vertices);
            }
            finally
            {
                File.Delete(path);
            }

            var cradle = Scene.Load("samples/scenes/newtons-cradle.json");
            var cradleWorld = cradle.Build();
            var integrator = IntegratorCatalog.Create("rk4");
            for (var step = 0; step < 500; step++)
            {
                cradleWorld.Step(integrator, 0.001);
            }

            Print("scene/newtons-cradle", StateHash(cradleWorld, integrator));

            // The flag in a gusty wind: the aerodynamics and the gust's own sines, under xpbd and implicit Euler.
            var flag = Scene.Load("samples/scenes/flag-in-wind.json");
            foreach (var name in new[] { "xpbd", "implicit-euler" })
            {
                var flagWorld = flag.Build();
                var flagIntegrator = IntegratorCatalog.Create(name);
                for (var step = 0; step < 120; step++)
                {
                    flagWorld.Step(flagIntegrator, flag.Settings.TimeStep);
                }

                Print("scene/flag-in-wind/" + name, StateHash(flagWorld, flagIntegrator));
            }

            // A cloth folding onto itself over a sphere: self-collision's grid, its particle-triangle and edge-edge
            // projections (one second, folds included).
            var fold = Scene.Load("samples/scenes/cloth-fold.json");
            var foldWorld = fold.Build();
            var foldIntegrator = IntegratorCatalog.Create(fold.Settings.Integrator, substeps: fold.Settings.Substeps);
            for (var step = 0; step < 60; step++)
            {
                foldWorld.Step(foldIntegrator, fold.Settings.TimeStep);
            }

            Print("scene/cloth-fold", StateHash(foldWorld, foldIntegrator));
        }

        // A decimal number of 1 to 25 digits (the first not 0), a point somewhere, an exponent from -300 to 280, from an LCG.
        private static string DecimalText(ref ulong seed)
        {
            var text = new System.Text.StringBuilder();
            var digits = 1 + (int)(Next(ref seed) % 25);
            var point = (int)(Next(ref seed) % (ulong)(digits + 1));
            if (Next(ref seed) % 2 == 0)
            {
                text.Append('-');
            }

            for (var d = 0; d < digits; d++)
            {
                if (d == point && d > 0)
                {
                    text.Append('.');
                }

                text.Append((char)((d == 0 ? '1' : '0') + (int)(Next(ref seed) % (d == 0 ? 9UL : 10UL)))); // JSON: no leading 0
            }

            var exponent = (int)(Next(ref seed) % 581) - 300; // at most 25 digits before the point: below 1e306
            return text.Append('e').Append(exponent.ToString(CultureInfo.InvariantCulture)).ToString();
        }

        private static ulong Next(ref ulong seed)
        {
            seed = (seed * 6364136223846793005UL) + 1442695040888963407UL;
            return seed >> 33;
        }

        private static ulong StateHash(ParticleWorld world, IIntegrator integrator)
        {
            var hash = new BitHash();
            hash.Add(world.Time);
            hash.Add(world.State);
            AddIntegratorState(hash, integrator);
            return hash.Value;
        }

        private static void AddIntegratorState(BitHash hash, IIntegrator integrator)
        {
            var stateful = integrator as IStatefulIntegrator;
            if (stateful != null)
            {
                var state = new double[stateful.StateLength];
                stateful.WriteState(state);
                hash.Add(state);
            }
        }

        private static double Median(double[] values)
        {
            var sorted = (double[])values.Clone();
            Array.Sort(sorted);
            return sorted[sorted.Length / 2];
        }

        private static void Require(bool condition, string message)
        {
            if (!condition)
            {
                throw new InvalidOperationException(message);
            }
        }

        private static void Print(string name, BitHash hash) => Print(name, hash.Value);

        private static void Print(string name, ulong hash) =>
            Console.WriteLine("hash " + name + " " + hash.ToString("x16", CultureInfo.InvariantCulture));

        // "count <case> cg-iterations-per-step <mean> (<iterations> in <steps> steps)": deterministic, the same on both
        // runtimes. The mean is rounded to a tenth in integers, half up: the runtimes format a double that falls on a
        // half differently (522 / 120 = 4.35 prints as 4.4 on Mono and 4.3 on CoreCLR), the integers do not.
        private static void PrintIterations(string name, long iterations, int steps)
        {
            var tenths = ((iterations * 10) + (steps / 2)) / steps;
            Console.WriteLine(string.Format(
                CultureInfo.InvariantCulture,
                "count {0} cg-iterations-per-step {1}.{2} ({3} in {4} steps)",
                name,
                tenths / 10,
                tenths % 10,
                iterations,
                steps));
        }

        // "time <case> <wall> <cpu> <unit>"; cpu is -1 where the thread's CPU time cannot be read.
        private static void PrintTime(string name, double wall, double cpu, string unit) =>
            Console.WriteLine(string.Format(CultureInfo.InvariantCulture, "time {0} {1:F3} {2:F3} {3}", name, wall, cpu, unit));

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

        /// <summary>The sample's mesh, read through the stand-in UnityEngine.</summary>
        private sealed class SampleHandle
        {
            private readonly UnityEngine.Mesh _mesh;

            public SampleHandle(UnityEngine.GameObject gameObject, SimulatedCloth component)
            {
                _mesh = gameObject.GetComponent<UnityEngine.MeshFilter>().sharedMesh;
                Component = component;
            }

            public SimulatedCloth Component { get; }

            public UnityEngine.Vector3[] MeshVertices() => _mesh.vertices;

            public UnityEngine.Vector3[] MeshNormals() => _mesh.normals;
        }
    }

    /// <summary>
    /// Wall time, and the CPU time of the calling thread (getrusage RUSAGE_THREAD on Linux, microseconds): on a machine
    /// that other work loads, the thread's CPU time leaves out the time it waited for a core, which wall time counts.
    /// </summary>
    internal sealed class Timer
    {
        private const int RusageThread = 1;
        private readonly Stopwatch _wall;
        private readonly double _cpuStart;

        private Timer()
        {
            _cpuStart = ThreadCpuMilliseconds();
            _wall = Stopwatch.StartNew();
        }

        public double WallMilliseconds => _wall.Elapsed.TotalMilliseconds;

        public double CpuMilliseconds
        {
            get
            {
                var now = ThreadCpuMilliseconds();
                return now < 0 || _cpuStart < 0 ? -1 : now - _cpuStart;
            }
        }

        public static Timer Start() => new Timer();

        private static double ThreadCpuMilliseconds()
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

    /// <summary>Counts how often each chunk runs, and whether a chunk was told another chunk count.</summary>
    internal sealed class CountedWork : IParallelWork
    {
        private readonly int[] _calls;
        private int _expectedCount;
        private int _wrongCount;

        public CountedWork(int capacity)
        {
            _calls = new int[capacity];
        }

        public void Expect(int chunkCount) => _expectedCount = chunkCount;

        public void Execute(int chunk, int chunkCount)
        {
            if (chunkCount != _expectedCount)
            {
                System.Threading.Interlocked.Exchange(ref _wrongCount, 1);
            }

            System.Threading.Interlocked.Increment(ref _calls[chunk]);
        }

        /// <summary>The first chunk that did not run exactly once (or ran though beyond the count), the count itself if
        /// a chunk was told another; -1 if all is well. Clears the counts.</summary>
        public int CheckAndClear(int chunkCount)
        {
            var wrong = _wrongCount != 0 ? chunkCount : -1;
            for (var chunk = 0; chunk < _calls.Length; chunk++)
            {
                if (_calls[chunk] != (chunk < chunkCount ? 1 : 0) && wrong < 0)
                {
                    wrong = chunk;
                }

                _calls[chunk] = 0;
            }

            _wrongCount = 0;
            return wrong;
        }
    }

    /// <summary>Each chunk waits until all the run's chunks have started (10 s at most, then it gives up).</summary>
    internal sealed class MeetingWork : IParallelWork
    {
        private readonly int _parties;
        private int _arrived;

        public MeetingWork(int parties)
        {
            _parties = parties;
        }

        public bool GaveUp { get; private set; }

        public void Reset() => _arrived = 0;

        public void Execute(int chunk, int chunkCount)
        {
            System.Threading.Interlocked.Increment(ref _arrived);
            var clock = Stopwatch.StartNew();
            var spinner = default(System.Threading.SpinWait);
            while (System.Threading.Volatile.Read(ref _arrived) < _parties)
            {
                if (clock.ElapsedMilliseconds > 10000)
                {
                    GaveUp = true;
                    return;
                }

                spinner.SpinOnce();
            }
        }
    }

    /// <summary>FNV-1a over 64-bit words: the raw bits of doubles, floats and integers, in order.</summary>
    internal sealed class BitHash
    {
        private const ulong Prime = 1099511628211;

        /// <summary>The hash so far.</summary>
        public ulong Value { get; private set; } = 14695981039346656037;

        public void Add(ulong word)
        {
            for (var i = 0; i < 8; i++)
            {
                Value = (Value ^ ((word >> (8 * i)) & 0xff)) * Prime;
            }
        }

        public void Add(long value) => Add(unchecked((ulong)value));

        public void Add(int value) => Add(unchecked((ulong)(uint)value));

        public void Add(double value) => Add(BitConverter.DoubleToInt64Bits(value));

        public void Add(ReadOnlySpan<double> values) => Add(values.ToArray());

        public void Add(double[] values)
        {
            Add(values.Length);
            foreach (var value in values)
            {
                Add(value);
            }
        }

        public void Add(float[] values)
        {
            Add(values.Length);
            var bits = new int[values.Length];
            Buffer.BlockCopy(values, 0, bits, 0, 4 * values.Length);
            foreach (var b in bits)
            {
                Add(b);
            }
        }

        public void Add(System.Numerics.Vector3[] values)
        {
            var floats = new float[3 * values.Length];
            for (var i = 0; i < values.Length; i++)
            {
                floats[3 * i] = values[i].X;
                floats[(3 * i) + 1] = values[i].Y;
                floats[(3 * i) + 2] = values[i].Z;
            }

            Add(floats);
        }

        public void Add(byte[] bytes)
        {
            Add(bytes.Length);
            foreach (var b in bytes)
            {
                Add((int)b);
            }
        }
    }
}
