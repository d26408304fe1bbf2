using System;
using System.Runtime.InteropServices;
using ParticlePhysics.Numerics;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Integrators;

/// <summary>
/// Extended position-based dynamics in small steps (Macklin et al., "XPBD", 2016, and "Small Steps in Physics
/// Simulation", 2019): the real-time path for games, stable at 60 Hz at any stiffness. It never sees forces: it asks
/// the system (<see cref="IPositionBasedSystem"/>) for the accelerations of the forces that are not projected, for one
/// projection pass of every constraint per substep, and for the velocity pass.
/// </summary>
/// <remarks>
/// Each step of h is split into <see cref="Substeps"/> substeps of h_s = h / n; each substep, from (x0, v0) at t:
/// a = a(t, x0, v0) (gravity, drag, unprojected forces); v = v0 + h_s a; x = x0 + h_s v (semi-implicit Euler, the
/// prediction); every constraint projected once (springs with compliance 1 / k, rods and cables with compliance 0,
/// contacts); v = (x - x0) / h_s (a pinned particle keeps its own velocity exactly); then one velocity pass
/// (restitution, friction). Derivation: one Gauss-Seidel iteration of the implicit Euler step on the constraints'
/// compliant energy per substep, with the multipliers reset each substep, converges to the implicit solution as the
/// substeps shrink ("Small Steps"), so the method is first order in h_s. Stability: a projection never adds
/// energy and a stiff constraint becomes rigid rather than unstable, so any h is stable for the projected forces;
/// the forces left to the prediction (drag, zero-rest-length springs without a projection, your own) keep
/// semi-implicit Euler's limit h_s omega &lt; 2 for them.
/// <para>
/// Cost: one pass over the particles for the prediction (it also saves x0 and v0), one projection pass, one pass for
/// the velocities, per substep; nothing is allocated once the buffers are sized. With a
/// <see cref="ParticleWorld.Runner"/> the velocity pass is split into ranges of particles, one hand-off (the
/// prediction too from 16 384 particles), and the springs' projection into two phases of groups of springs that share
/// no particle (<see cref="Constraints.SpringProjection"/>), one hand-off each: three per substep on the 64 x 64
/// cloth, four on the 128 x 128 one and larger ones. Every value is then
/// computed by the same operations as on one core, so the result is bit-identical. Nothing else can be folded into
/// those hand-offs without the integrator seeing forces or constraints: between the velocity pass and the next
/// prediction the world computes the unprojected accelerations (forces of the new velocities) and solves the
/// constraints' velocities, and the projection between the two passes belongs to the constraint sets.
/// </para>
/// </remarks>
public sealed class Xpbd : IPositionBasedIntegrator
{
    /// <summary>The default number of substeps per step: 10.</summary>
    public const int DefaultSubsteps = 10;

    /// <summary>The most substeps per step: 1000.</summary>
    public const int MaxSubsteps = 1000;

    // The velocity pass is split over a runner only when each chunk gets at least this many particles: below it, waking
    // another core costs more than the pass.
    private const int MinParticlesPerChunk = 1024;

    // The prediction only from this many particles per chunk. It comes right after the world's accelerations, which run
    // on the calling thread, so a worker may have to be woken, which costs more than half a small pass saves; left on
    // the calling thread, the prediction lets the projection's first phase wake the worker while the calling thread
    // already projects. From 8192 particles per chunk (the 128 x 128 cloth) half the pass saves more than that.
    private const int MinParticlesPerPredictionChunk = 8192;

    private int _substeps = DefaultSubsteps;
    private double[]? _startPositions;
    private double[]? _startVelocities;
    private double[]? _accelerations;
    private readonly ParticlePass _prediction = new(prediction: true);
    private readonly ParticlePass _velocities = new(prediction: false);

    /// <summary>An integrator with <see cref="DefaultSubsteps"/> substeps per step.</summary>
    public Xpbd()
    {
    }

    /// <summary>An integrator with <paramref name="substeps"/> substeps per step (1 to 1000).</summary>
    public Xpbd(int substeps)
    {
        Substeps = substeps;
    }

    /// <inheritdoc />
    public string Name => "xpbd";

    /// <inheritdoc />
    public int Order => 1;

    /// <summary>
    /// The number of substeps each step is split into, one projection pass each: a whole number from 1 to 1000
    /// (default 10). More substeps make long chains of stiff constraints converge (a chain's error grows with its
    /// length and falls with the substeps), at the cost of one pass each.
    /// </summary>
    public int Substeps
    {
        get => _substeps;
        set
        {
            if (value < 1 || value > MaxSubsteps)
            {
                throw new ArgumentOutOfRangeException(
                    nameof(Substeps), value, $"Substeps must be a whole number from 1 to {MaxSubsteps}; got {value}.");
            }

            _substeps = value;
        }
    }

    /// <inheritdoc />
    public void Step(IOdeSystem system, double time, ReadOnlySpan<double> state, Span<double> next, double dt)
    {
        StepChecks.Check(system, state, next, dt);
        var positionBased = system as IPositionBasedSystem ?? throw new ArgumentException(
            $"xpbd needs a position-based system (IPositionBasedSystem), such as a ParticleWorld; {system.GetType().Name} "
            + "is not one. Use explicit-euler, rk4 or rk45 for it.",
            nameof(system));
        var n = positionBased.CoordinateCount;
        var w = positionBased.InverseMasses;
        if (2 * n != state.Length || 3 * w.Length != n)
        {
            throw new ArgumentException(
                $"The system has {n} coordinates and {w.Length} inverse masses: it needs 3 coordinates per particle and a "
                + $"state of {2 * n} values, and the state has {state.Length}.",
                nameof(system));
        }

        var x0 = _startPositions = StepChecks.Sized(_startPositions, n);
        var v0 = _startVelocities = StepChecks.Sized(_startVelocities, n);
        var a = _accelerations = StepChecks.Sized(_accelerations, n);
        state.CopyTo(next);
        var x = next.Slice(0, n);
        var v = next.Slice(n, n);
        var h = dt / _substeps;
        var inverseH = 1.0 / h;
        var particles = w.Length;
        var parallelism = positionBased.Runner is { MaxParallelism: > 1 } runner ? runner.MaxParallelism : 1;
        var predictionChunks = Math.Min(parallelism, particles / MinParticlesPerPredictionChunk);
        var velocityChunks = Math.Min(parallelism, particles / MinParticlesPerChunk);
        for (var s = 0; s < _substeps; s++)
        {
            var t = time + (s * h);

            // The accelerations at the substep's start: x and v still hold x0 and v0.
            positionBased.ComputeUnprojectedAccelerations(t, x, v, a);
            unsafe
            {
                // The five buffers hold n = 3 x particles values (checked above, and sized to n): no pointer leaves them.
                fixed (double* xp = x, vp = v, x0p = x0, v0p = v0, ap = a)
                {
                    if (predictionChunks > 1)
                    {
                        _prediction.Set(xp, vp, x0p, v0p, ap, null, h, particles);
                        positionBased.Runner!.Run(_prediction, predictionChunks);
                    }
                    else
                    {
                        Predict(xp, vp, x0p, v0p, ap, h, 0, particles);
                    }
                }
            }

            positionBased.ProjectConstraints(t, h, x0, v0, x, v);
            unsafe
            {
                fixed (double* xp = x, vp = v, x0p = x0, wp = &MemoryMarshal.GetReference(w))
                {
                    if (velocityChunks > 1)
                    {
                        _velocities.Set(xp, vp, x0p, null, null, wp, inverseH, particles);
                        positionBased.Runner!.Run(_velocities, velocityChunks);
                    }
                    else
                    {
                        TakeVelocities(xp, vp, x0p, wp, inverseH, 0, particles);
                    }
                }
            }

            positionBased.SolveConstraintVelocities(t, h, x0, v0, x, v);
        }
    }

    /// <summary>
    /// The prediction for particles [begin, end): x0 = x, v0 = v (the substep's start, kept for the projections), then
    /// v = v0 + h a, x = x0 + h v (semi-implicit Euler), with SIMD where the runtime accelerates it.
    /// </summary>
    private static unsafe void Predict(double* x, double* v, double* x0, double* v0, double* a, double h, int begin, int end)
    {
        var o = 3L * begin;
        var length = 3 * (end - begin);
        VectorKernels.Predict(
            new Span<double>(x + o, length),
            new Span<double>(v + o, length),
            new Span<double>(x0 + o, length),
            new Span<double>(v0 + o, length),
            new ReadOnlySpan<double>(a + o, length),
            h);
    }

    /// <summary>v = (x - x0) / h for particles [begin, end); a pinned particle moves at exactly its own velocity.</summary>
    private static unsafe void TakeVelocities(double* x, double* v, double* x0, double* w, double inverseH, int begin, int end)
    {
        var o = 3L * begin;
        double* xi = x + o, vi = v + o, x0i = x0 + o;
        for (double* wi = w + begin, last = w + end; wi < last; wi++, xi += 3, vi += 3, x0i += 3)
        {
            if (*wi == 0.0)
            {
                continue;
            }

            vi[0] = (xi[0] - x0i[0]) * inverseH;
            vi[1] = (xi[1] - x0i[1]) * inverseH;
            vi[2] = (xi[2] - x0i[2]) * inverseH;
        }
    }

    /// <summary>One of the two particle passes over the runner's chunks, each chunk a range of particles.</summary>
    private sealed unsafe class ParticlePass : IParallelWork
    {
        private readonly bool _prediction;
        private double* _x;
        private double* _v;
        private double* _x0;
        private double* _v0;
        private double* _a;
        private double* _w;
        private double _step; // h for the prediction, 1 / h for the velocities
        private int _particles;

        public ParticlePass(bool prediction)
        {
            _prediction = prediction;
        }

        public void Set(double* x, double* v, double* x0, double* v0, double* a, double* w, double step, int particles)
        {
            _x = x;
            _v = v;
            _x0 = x0;
            _v0 = v0;
            _a = a;
            _w = w;
            _step = step;
            _particles = particles;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _particles);
            if (_prediction)
            {
                Predict(_x, _v, _x0, _v0, _a, _step, begin, end);
            }
            else
            {
                TakeVelocities(_x, _v, _x0, _w, _step, begin, end);
            }
        }
    }
}
