using System;
using System.Runtime.InteropServices;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Constraints;

/// <summary>
/// The springs of a generator (<see cref="Forces.SpringNetwork"/>, <see cref="Forces.ZeroLengthSprings"/>, any
/// <see cref="ISpringElements"/>) as XPBD distance constraints under the position-based integrator: the world then
/// leaves the springs out of the forces and this set projects each one once per substep, with compliance
/// alpha = 1 / k and the spring's damping. Under the force-based integrators it does nothing: the springs act as forces.
/// </summary>
/// <remarks>
/// <para>
/// A spring of stiffness k, rest length L and axial damping c is the constraint C = |x_i - x_j| - L with compliance
/// alpha = 1 / k and damping beta = c (its force -k C grad C - c (grad C . v) grad C). One XPBD iteration per substep
/// with the multiplier reset (Macklin, Mueller and Chentanez, "XPBD", 2016, with its damping; "Small Steps", 2019):
/// dlambda = (-C - gamma grad C . (x - x0)) / ((1 + gamma) w + alpha / h^2) with gamma = alpha beta / h and
/// w = w_i + w_j. Multiplied through by k h^2 it reads dlambda = -(k h^2 C + c h grad C . (x - x0)) / ((k h^2 + c h) w + 1),
/// which stays finite for k = 0 (a pure damper) and tends to the rigid -C / w as k grows: stable at any stiffness.
/// Then x_i += w_i dlambda u, x_j -= w_j dlambda u with u = (x_i - x_j) / |x_i - x_j|. A mass m hanging at rest on
/// such a spring is a fixed point of the substep exactly when the stretch is m g alpha, whatever h.
/// </para>
/// <para>
/// The springs are projected in colour order (<see cref="ConstraintColouring"/>, recomputed only when the generator's
/// <see cref="ISpringElements.TopologyVersion"/> changes), from flat arrays copied in that order (again when
/// <see cref="ISpringElements.ParameterVersion"/> changes): no virtual call and no allocation per spring or per step.
/// Within a colour the pair springs come first, then the anchored ones; no two springs of a colour share a particle,
/// so their order within it changes no bit. That is what lets a colour be split over the world's
/// <see cref="ParticleWorld.Runner"/>: each chunk projects a range of the colour, and the result is bit-identical to
/// one core's.
/// </para>
/// </remarks>
public sealed class SpringProjection : IForceProjection
{
    // A colour is split over the runner only when each of its chunks gets at least this many springs: below it,
    // handing the work to another core costs more than it saves.
    private const int MinSpringsPerChunk = 256;

    private readonly ISpringElements _springs;
    private readonly ColourPass _pass = new();
    private int _topologyVersion = -1;
    private int _parameterVersion = -1;
    private int _particles = -1;
    private int _count;

    // The hot data, in colour order: per colour its pair springs, then its anchored ones, each spring's k h^2 and c h
    // for the substep they were prepared for (_preparedStep), beside its ends and rest length. One array of structs
    // each, so that the projection loop walks one pointer and holds few registers.
    private PairSpring[] _pairs = Array.Empty<PairSpring>();
    private AnchoredSpring[] _anchored = Array.Empty<AnchoredSpring>();
    private int[] _pairStarts = { 0 };
    private int[] _anchoredStarts = { 0 };
    private double _preparedStep = double.NaN;

    // The parameters (k, c per spring) in the same order, from which each substep length is prepared.
    private double[] _pairCoefficients = Array.Empty<double>();
    private double[] _anchoredCoefficients = Array.Empty<double>();
    private int[] _order = Array.Empty<int>();
    private int[] _colourStarts = { 0 };

    // The generator's own layout, copied when its versions change.
    private int[] _pairFirst = Array.Empty<int>();
    private int[] _pairSecond = Array.Empty<int>();
    private double[] _pairParameters = Array.Empty<double>();
    private int[] _anchoredParticle = Array.Empty<int>();
    private double[] _anchoredParameters = Array.Empty<double>();

    /// <summary>The projection of <paramref name="springs"/>; add it to the world that holds them with <see cref="ParticleWorld.AddConstraints"/>.</summary>
    public SpringProjection(ISpringElements springs)
    {
        Guard.NotNull(springs, nameof(springs));
        _springs = springs;
    }

    /// <inheritdoc />
    public IForceGenerator Force => _springs;

    /// <summary>The number of colours (independent batches) of the last projection: 0 before the first.</summary>
    public int ColourCount => _colourStarts.Length - 1;

    /// <summary>
    /// The springs in the order they are projected (indices: the pair springs, then the anchored ones after them): by
    /// colour, and within a colour its pair springs, then its anchored ones.
    /// </summary>
    public ReadOnlySpan<int> ProjectionOrder => _order.AsSpan(0, _count);

    /// <summary>Where each colour starts in <see cref="ProjectionOrder"/>, with a last entry equal to the spring count.</summary>
    public ReadOnlySpan<int> ColourStarts => _colourStarts;

    /// <inheritdoc />
    /// <remarks>Nothing: under the force-based integrators the springs act as forces.</remarks>
    public void Resolve(in ConstraintContext context)
    {
    }

    /// <inheritdoc />
    public void Project(in ConstraintContext context)
    {
        Refresh(context.Count);
        var h = context.Dt;
        if (h != _preparedStep)
        {
            Prepare(h);
        }

        var runner = context.Runner is { MaxParallelism: > 1 } r ? r : null;
        unsafe
        {
            // Every index in _pairs and _anchored was checked against the particle count in Refresh, and the context
            // checked that positions, start positions and inverse masses hold that many particles: no pointer below
            // leaves its array.
            fixed (double* x = context.Positions, x0 = &MemoryMarshal.GetReference(context.StartPositions))
            fixed (double* w = &MemoryMarshal.GetReference(context.InverseMasses))
            fixed (PairSpring* pairs = _pairs)
            fixed (AnchoredSpring* anchored = _anchored)
            {
                for (var c = 0; c + 1 < _colourStarts.Length; c++)
                {
                    int pairBegin = _pairStarts[c], pairEnd = _pairStarts[c + 1];
                    int anchoredBegin = _anchoredStarts[c], anchoredEnd = _anchoredStarts[c + 1];
                    var size = pairEnd - pairBegin + (anchoredEnd - anchoredBegin);
                    var chunks = runner is null ? 1 : Math.Min(2 * runner.MaxParallelism, size / MinSpringsPerChunk);
                    if (chunks > 1)
                    {
                        _pass.Set(pairs, pairBegin, pairEnd, anchored, anchoredBegin, anchoredEnd, x, x0, w);
                        runner!.Run(_pass, chunks);
                        continue;
                    }

                    ProjectPairs(pairs, pairBegin, pairEnd, x, x0, w);
                    ProjectAnchored(anchored, anchoredBegin, anchoredEnd, x, x0, w);
                }
            }
        }
    }

    /// <inheritdoc />
    /// <remarks>Nothing: the damping is in the projection.</remarks>
    public void SolveVelocities(in ConstraintContext context)
    {
    }

    /// <summary>
    /// Projects the pair springs [begin, end) once, in order: the hot loop of xpbd. The formula and its derivation are
    /// in the class remarks: dlambda = -(k h^2 C + c h u . dx) / ((k h^2 + c h) w + 1).
    /// </summary>
    private static unsafe void ProjectPairs(PairSpring* springs, int begin, int end, double* x, double* x0, double* w)
    {
        for (PairSpring* p = springs + begin, last = springs + end; p < last; p++)
        {
            // Unsigned ends (checked in Refresh), so that widening them to 64-bit offsets costs nothing.
            uint a = p->First, b = p->Second;
            double wi = w[a], wj = w[b];
            var wsum = wi + wj;
            if (wsum == 0.0)
            {
                continue;
            }

            double* xi = x + (3L * a), xj = x + (3L * b), x0i = x0 + (3L * a), x0j = x0 + (3L * b);
            double xi0 = xi[0], xi1 = xi[1], xi2 = xi[2], xj0 = xj[0], xj1 = xj[1], xj2 = xj[2];
            double dx = xi0 - xj0, dy = xi1 - xj1, dz = xi2 - xj2;
            var mx = (xi0 - x0i[0]) - (xj0 - x0j[0]);
            var my = (xi1 - x0i[1]) - (xj1 - x0j[1]);
            var mz = (xi2 - x0i[2]) - (xj2 - x0j[2]);
            var squared = (dx * dx) + (dy * dy) + (dz * dz);
            if (squared == 0.0)
            {
                continue; // no direction, as the force is zero there
            }

            var l = Math.Sqrt(squared);
            var inverse = 1.0 / l;
            double ux = dx * inverse, uy = dy * inverse, uz = dz * inverse;
            var moved = (ux * mx) + (uy * my) + (uz * mz);
            var dlambda = -((p->Stiffness * (l - p->RestLength)) + (p->Damping * moved))
                / (((p->Stiffness + p->Damping) * wsum) + 1.0);
            double cx = dlambda * ux, cy = dlambda * uy, cz = dlambda * uz;

            // The two ends are distinct particles (checked in Refresh), so the values read above are still theirs.
            xi[0] = xi0 + (wi * cx);
            xi[1] = xi1 + (wi * cy);
            xi[2] = xi2 + (wi * cz);
            xj[0] = xj0 - (wj * cx);
            xj[1] = xj1 - (wj * cy);
            xj[2] = xj2 - (wj * cz);
        }
    }

    /// <summary>Projects the anchored springs [begin, end) once: the pair formula with a fixed end (w_j = 0, x0_j = x_j).</summary>
    private static unsafe void ProjectAnchored(AnchoredSpring* springs, int begin, int end, double* x, double* x0, double* w)
    {
        for (var s = begin; s < end; s++)
        {
            var p = springs + s;
            var wi = w[p->Particle];
            if (wi == 0.0)
            {
                continue;
            }

            long i = 3L * p->Particle;
            double dx = x[i] - p->AnchorX, dy = x[i + 1] - p->AnchorY, dz = x[i + 2] - p->AnchorZ;
            double mx = x[i] - x0[i], my = x[i + 1] - x0[i + 1], mz = x[i + 2] - x0[i + 2];
            var squared = (dx * dx) + (dy * dy) + (dz * dz);
            if (squared == 0.0)
            {
                continue;
            }

            var l = Math.Sqrt(squared);
            var inverse = 1.0 / l;
            double ux = dx * inverse, uy = dy * inverse, uz = dz * inverse;
            var moved = (ux * mx) + (uy * my) + (uz * mz);
            var dlambda = -((p->Stiffness * (l - p->RestLength)) + (p->Damping * moved))
                / (((p->Stiffness + p->Damping) * wi) + 1.0);
            x[i] += wi * (dlambda * ux);
            x[i + 1] += wi * (dlambda * uy);
            x[i + 2] += wi * (dlambda * uz);
        }
    }

    /// <summary>k h^2 and c h of every spring for the substep h, in the projection order.</summary>
    private void Prepare(double h)
    {
        var hh = h * h;
        for (var s = 0; s < _pairs.Length; s++)
        {
            _pairs[s].Stiffness = _pairCoefficients[2 * s] * hh;
            _pairs[s].Damping = _pairCoefficients[(2 * s) + 1] * h;
        }

        for (var s = 0; s < _anchored.Length; s++)
        {
            _anchored[s].Stiffness = _anchoredCoefficients[2 * s] * hh;
            _anchored[s].Damping = _anchoredCoefficients[(2 * s) + 1] * h;
        }

        _preparedStep = h;
    }

    /// <summary>Recolours when the springs' topology changed, and recopies their parameters when they changed.</summary>
    private void Refresh(int particles)
    {
        var topology = _springs.TopologyVersion;
        var parameters = _springs.ParameterVersion;
        if (topology == _topologyVersion && parameters == _parameterVersion && particles == _particles)
        {
            return;
        }

        int pairs = _springs.PairCount, anchored = _springs.AnchoredCount;
        var count = pairs + anchored;
        var recolour = topology != _topologyVersion || particles != _particles || count != _count;
        if (recolour)
        {
            _pairFirst = new int[pairs];
            _pairSecond = new int[pairs];
            _pairParameters = new double[3 * pairs];
            _anchoredParticle = new int[anchored];
            _anchoredParameters = new double[6 * anchored];
            _order = new int[count];
        }

        _springs.CopyPairs(_pairFirst, _pairSecond, _pairParameters);
        _springs.CopyAnchored(_anchoredParticle, _anchoredParameters);
        for (var p = 0; p < pairs; p++)
        {
            if ((uint)_pairFirst[p] >= (uint)particles || (uint)_pairSecond[p] >= (uint)particles)
            {
                throw new ArgumentException(
                    $"Spring {p} joins particles {_pairFirst[p]} and {_pairSecond[p]}, but the world has {particles}.");
            }

            if (_pairFirst[p] == _pairSecond[p])
            {
                throw new ArgumentException($"Spring {p} joins particle {_pairFirst[p]} to itself: a spring needs two particles.");
            }
        }

        for (var a = 0; a < anchored; a++)
        {
            if ((uint)_anchoredParticle[a] >= (uint)particles)
            {
                throw new ArgumentException(
                    $"Anchored spring {a} holds particle {_anchoredParticle[a]}, but the world has {particles}.");
            }
        }

        if (recolour)
        {
            Recolour(pairs, anchored, particles);
        }

        // The parameters in the projection order (the ends, rest lengths and anchors straight into the hot arrays):
        // the k-th pair spring of _order is _pairs[k's rank among the pairs], and likewise for the anchored ones.
        int nextPair = 0, nextAnchored = 0;
        for (var k = 0; k < count; k++)
        {
            var source = _order[k];
            if (source < pairs)
            {
                var s = nextPair++;
                _pairs[s].First = (uint)_pairFirst[source];
                _pairs[s].Second = (uint)_pairSecond[source];
                _pairs[s].RestLength = _pairParameters[(3 * source) + 1];
                _pairCoefficients[2 * s] = _pairParameters[3 * source];
                _pairCoefficients[(2 * s) + 1] = _pairParameters[(3 * source) + 2];
            }
            else
            {
                var s = nextAnchored++;
                var a = source - pairs;
                _anchored[s].Particle = _anchoredParticle[a];
                _anchored[s].AnchorX = _anchoredParameters[6 * a];
                _anchored[s].AnchorY = _anchoredParameters[(6 * a) + 1];
                _anchored[s].AnchorZ = _anchoredParameters[(6 * a) + 2];
                _anchored[s].RestLength = _anchoredParameters[(6 * a) + 4];
                _anchoredCoefficients[2 * s] = _anchoredParameters[(6 * a) + 3];
                _anchoredCoefficients[(2 * s) + 1] = _anchoredParameters[(6 * a) + 5];
            }
        }

        _preparedStep = double.NaN;
        _count = count;
        _particles = particles;
        _topologyVersion = topology;
        _parameterVersion = parameters;
    }

    /// <summary>
    /// Colours the springs in their own index order (pairs, then anchored with second end -1), then lays each colour
    /// out as its pairs followed by its anchored springs: <see cref="ProjectionOrder"/>, and the batch starts.
    /// </summary>
    private void Recolour(int pairs, int anchored, int particles)
    {
        var count = pairs + anchored;
        var first = new int[count];
        var second = new int[count];
        _pairFirst.AsSpan().CopyTo(first);
        _pairSecond.AsSpan().CopyTo(second);
        for (var a = 0; a < anchored; a++)
        {
            first[pairs + a] = _anchoredParticle[a];
            second[pairs + a] = -1;
        }

        var byColour = new int[count];
        _colourStarts = ConstraintColouring.Colour(first, second, count, particles, byColour);
        var colours = _colourStarts.Length - 1;
        _pairStarts = new int[colours + 1];
        _anchoredStarts = new int[colours + 1];
        var next = 0;
        for (var c = 0; c < colours; c++)
        {
            // Stable within the colour: its pairs in index order, then its anchored springs in index order.
            _pairStarts[c + 1] = _pairStarts[c];
            _anchoredStarts[c + 1] = _anchoredStarts[c];
            for (var k = _colourStarts[c]; k < _colourStarts[c + 1]; k++)
            {
                if (byColour[k] < pairs)
                {
                    _order[next++] = byColour[k];
                    _pairStarts[c + 1]++;
                }
            }

            for (var k = _colourStarts[c]; k < _colourStarts[c + 1]; k++)
            {
                if (byColour[k] >= pairs)
                {
                    _order[next++] = byColour[k];
                    _anchoredStarts[c + 1]++;
                }
            }
        }

        _pairs = new PairSpring[pairs];
        _anchored = new AnchoredSpring[anchored];
        _pairCoefficients = new double[2 * pairs];
        _anchoredCoefficients = new double[2 * anchored];
    }

    /// <summary>A spring between two particles as the projection reads it: 32 bytes.</summary>
    [StructLayout(LayoutKind.Sequential)]
    private struct PairSpring
    {
        public uint First;
        public uint Second;
        public double Stiffness; // k h^2
        public double Damping; // c h
        public double RestLength;
    }

    /// <summary>A spring from a particle to a fixed anchor as the projection reads it: 56 bytes.</summary>
    [StructLayout(LayoutKind.Sequential)]
    private struct AnchoredSpring
    {
        public int Particle;
        public double AnchorX;
        public double AnchorY;
        public double AnchorZ;
        public double Stiffness; // k h^2
        public double Damping; // c h
        public double RestLength;
    }

    /// <summary>One colour over the runner's chunks: each chunk projects its share of the colour's pairs and anchored springs.</summary>
    private sealed unsafe class ColourPass : IParallelWork
    {
        private PairSpring* _pairs;
        private AnchoredSpring* _anchored;
        private double* _x;
        private double* _x0;
        private double* _w;
        private int _pairBegin;
        private int _pairEnd;
        private int _anchoredBegin;
        private int _anchoredEnd;

        public void Set(
            PairSpring* pairs, int pairBegin, int pairEnd, AnchoredSpring* anchored, int anchoredBegin, int anchoredEnd,
            double* x, double* x0, double* w)
        {
            _pairs = pairs;
            _pairBegin = pairBegin;
            _pairEnd = pairEnd;
            _anchored = anchored;
            _anchoredBegin = anchoredBegin;
            _anchoredEnd = anchoredEnd;
            _x = x;
            _x0 = x0;
            _w = w;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (pairBegin, pairEnd) = Chunk.Range(chunk, chunkCount, _pairEnd - _pairBegin);
            ProjectPairs(_pairs, _pairBegin + pairBegin, _pairBegin + pairEnd, _x, _x0, _w);
            var (anchoredBegin, anchoredEnd) = Chunk.Range(chunk, chunkCount, _anchoredEnd - _anchoredBegin);
            ProjectAnchored(_anchored, _anchoredBegin + anchoredBegin, _anchoredBegin + anchoredEnd, _x, _x0, _w);
        }
    }
}
