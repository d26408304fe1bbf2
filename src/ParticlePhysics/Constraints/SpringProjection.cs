using System;
using System.Runtime.CompilerServices;
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
/// which stays finite for k = 0 (a pure damper) and tends to the rigid -C / w as k grows: stable at any stiffness. Where
/// (k h^2 + c h) w overflows (k near double.MaxValue on a light particle) the same value is computed divided through by
/// k h^2 + c h, so that the limit is reached rather than lost to an infinite denominator.
/// Then x_i += w_i dlambda u, x_j -= w_j dlambda u with u = (x_i - x_j) / |x_i - x_j|. A mass m hanging at rest on
/// such a spring is a fixed point of the substep exactly when the stretch is m g alpha, whatever h.
/// </para>
/// <para>
/// The order (recomputed only when the generator's <see cref="ISpringElements.TopologyVersion"/> changes): the springs
/// coloured (<see cref="ConstraintColouring"/>: no two springs of a colour share a particle), each colour laid out as
/// its pair springs, then its anchored ones; then the particles split into <see cref="PartCount"/> parts of
/// contiguous indices (<see cref="ConstraintPartition"/>: a function of the particle count and the topology, never of
/// the runner), and that colour order distributed, stably, over one group per part: first the even parts, each with
/// its interior (the springs with every end in it; an anchored spring has one end, so it is always in its particle's
/// part) and its seams (the springs from it to an odd neighbour), then the odd parts' interiors. Each group is a list
/// of batches, its springs of one colour, which share no particle, so their order within a batch changes no bit. The
/// groups of one phase (the even parts; the odd parts) share no particle either, so a pass has two synchronisation
/// points. With one part (small worlds, and networks whose index order is not spatial) the order is the plain colour
/// order.
/// </para>
/// <para>
/// The same order whatever runs it: on one core the groups run one after the other; with the world's
/// <see cref="ParticleWorld.Runner"/> a phase of several groups is one hand-off, each chunk a range of whole groups,
/// and a phase of one group hands each batch large enough over as ranges of the batch. Every spring sees the same
/// values either way, so the result is bit-identical to one core's. The springs are projected from flat arrays
/// copied in that order (again when <see cref="ISpringElements.ParameterVersion"/> changes): no virtual call and no
/// allocation per spring or per step.
/// </para>
/// </remarks>
public sealed partial class SpringProjection : IForceProjection
{
    // A phase of several groups goes to the runner in one hand-off, and a batch of a phase of one group (P = 1) in one
    // hand-off of its own, only when each chunk gets at least this many springs: below it, handing the work to another
    // core costs more than it saves.
    private const int MinSpringsPerChunk = 256;

    private readonly ISpringElements _springs;
    private readonly GroupPass _groupPass = new();
    private readonly BatchPass _batchPass = new();
    private int _topologyVersion = -1;
    private int _parameterVersion = -1;
    private int _particles = -1;
    private int _count;

    // The hot data, in projection order: per batch its pair springs, then its anchored ones, each spring's k h^2 and
    // c h for the substep they were prepared for (_preparedStep), beside its ends and rest length. One array of structs
    // each, so that the projection loop walks one pointer and holds few registers.
    private PairSpring[] _pairs = Array.Empty<PairSpring>();
    private AnchoredSpring[] _anchored = Array.Empty<AnchoredSpring>();
    private double _preparedStep = double.NaN;

    // Every pair spring without damping: the projection then skips the damping's terms (the start positions and the
    // move along the spring), a third of the memory each spring reads. The same values: c h (u . dx) adds 0.
    private bool _undamped;

    // The layout (ConstraintPartition): batch b is _pairs[_pairStarts[b] ..] and _anchored[_anchoredStarts[b] ..];
    // group g is the batches [_groupBatchStarts[g], _groupBatchStarts[g + 1]); phase f the groups
    // [_phaseStarts[f], _phaseStarts[f + 1]).
    private int[] _pairStarts = { 0 };
    private int[] _anchoredStarts = { 0 };
    private int[] _groupBatchStarts = { 0 };
    private int[] _phaseStarts = { 0 };
    private int[] _groupStarts = { 0 };
    private int[] _batchStarts = { 0 };
    private int[] _partStarts = { 0 };
    private int _colours;

    // The parameters (k, c per spring) in the same order, from which each substep length is prepared.
    private double[] _pairCoefficients = Array.Empty<double>();
    private double[] _anchoredCoefficients = Array.Empty<double>();
    private int[] _order = Array.Empty<int>();

    /// <summary>The projection of <paramref name="springs"/>; add it to the world that holds them with <see cref="ParticleWorld.AddConstraints"/>.</summary>
    public SpringProjection(ISpringElements springs)
    {
        Guard.NotNull(springs, nameof(springs));
        _springs = springs;
    }

    /// <inheritdoc />
    public IForceGenerator Force => _springs;

    /// <summary>The number of colours of the springs' colouring (<see cref="ConstraintColouring"/>): 0 before the first projection.</summary>
    public int ColourCount => _colours;

    /// <summary>
    /// The number P of parts the particles are split into (contiguous index ranges; <see cref="ConstraintPartition"/>):
    /// 1 for small worlds and for networks whose index order is not spatial; 0 before the first projection.
    /// </summary>
    public int PartCount => _partStarts.Length - 1;

    /// <summary>Part p is the particles [PartStarts[p], PartStarts[p + 1]): <see cref="PartCount"/> + 1 entries.</summary>
    public ReadOnlySpan<int> PartStarts => _partStarts;

    /// <summary>
    /// The springs in the order they are projected (indices: the pair springs, then the anchored ones after them):
    /// group by group (<see cref="GroupStarts"/>), within a group batch by batch (<see cref="BatchStarts"/>), within a
    /// batch its pair springs, then its anchored ones. With one part, that is the colour order.
    /// </summary>
    public ReadOnlySpan<int> ProjectionOrder => _order.AsSpan(0, _count);

    /// <summary>
    /// Where each group starts in <see cref="ProjectionOrder"/>, with a last entry equal to the spring count: one group
    /// per part, the even parts first (group g &lt; P / 2 is part 2 g: its interior and its seams, the springs from it to
    /// an odd part), then the odd parts (group P / 2 + g is part 2 g + 1: its interior).
    /// </summary>
    public ReadOnlySpan<int> GroupStarts => _groupStarts;

    /// <summary>
    /// Where each phase starts among the groups, with a last entry equal to the group count: { 0, P / 2, P } (the even
    /// parts, then the odd ones), or { 0, 1 } with one part. The groups of one phase share no particle, so a runner
    /// takes a phase in one hand-off.
    /// </summary>
    public ReadOnlySpan<int> PhaseStarts => _phaseStarts;

    /// <summary>
    /// Where each batch starts in <see cref="ProjectionOrder"/>, with a last entry equal to the spring count: a batch is
    /// the springs of one colour within one group, and no two of them share a particle. With one part the batches are
    /// the colours.
    /// </summary>
    public ReadOnlySpan<int> BatchStarts => _batchStarts;

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
                for (var f = 0; f + 1 < _phaseStarts.Length; f++)
                {
                    int groupBegin = _phaseStarts[f], groupEnd = _phaseStarts[f + 1];
                    if (runner is not null && groupEnd - groupBegin > 1)
                    {
                        // The groups of a phase share no particle: one hand-off, each chunk a range of whole groups.
                        var springs = _groupStarts[groupEnd] - _groupStarts[groupBegin];
                        var chunks = Math.Min(groupEnd - groupBegin, springs / MinSpringsPerChunk);
                        if (chunks > 1)
                        {
                            _groupPass.Set(this, groupBegin, groupEnd, pairs, anchored, x, x0, w);
                            runner.Run(_groupPass, chunks);
                            continue;
                        }
                    }
                    else if (runner is not null)
                    {
                        // One group (one part): each batch as large as a colour, one hand-off each when it pays.
                        ProjectBatchesSplit(runner, groupBegin, pairs, anchored, x, x0, w);
                        continue;
                    }

                    ProjectGroups(groupBegin, groupEnd, pairs, anchored, x, x0, w);
                }
            }
        }
    }

    /// <inheritdoc />
    /// <remarks>Nothing: the damping is in the projection.</remarks>
    public void SolveVelocities(in ConstraintContext context)
    {
    }

    /// <summary>Projects the groups [begin, end) one after the other, each batch by batch: pairs, then anchored springs.</summary>
    private unsafe void ProjectGroups(
        int begin, int end, PairSpring* pairs, AnchoredSpring* anchored, double* x, double* x0, double* w)
    {
        for (var b = _groupBatchStarts[begin]; b < _groupBatchStarts[end]; b++)
        {
            if (_undamped)
            {
                ProjectUndampedPairs(pairs, _pairStarts[b], _pairStarts[b + 1], x, w);
            }
            else
            {
                ProjectPairs(pairs, _pairStarts[b], _pairStarts[b + 1], x, x0, w);
            }

            int anchoredBegin = _anchoredStarts[b], anchoredEnd = _anchoredStarts[b + 1];
            if (anchoredBegin < anchoredEnd)
            {
                ProjectAnchored(anchored, anchoredBegin, anchoredEnd, x, x0, w); // (a call saved per batch on a plain cloth)
            }
        }
    }

    /// <summary>
    /// Projects group <paramref name="group"/> batch by batch, each batch large enough split into ranges over the
    /// runner (its springs share no particle, so any split gives the same bits).
    /// </summary>
    private unsafe void ProjectBatchesSplit(
        IParallelRunner runner, int group, PairSpring* pairs, AnchoredSpring* anchored, double* x, double* x0, double* w)
    {
        for (var b = _groupBatchStarts[group]; b < _groupBatchStarts[group + 1]; b++)
        {
            int pairBegin = _pairStarts[b], pairEnd = _pairStarts[b + 1];
            int anchoredBegin = _anchoredStarts[b], anchoredEnd = _anchoredStarts[b + 1];
            var size = pairEnd - pairBegin + (anchoredEnd - anchoredBegin);
            var chunks = Math.Min(2 * runner.MaxParallelism, size / MinSpringsPerChunk);
            if (chunks > 1)
            {
                _batchPass.Set(pairs, pairBegin, pairEnd, anchored, anchoredBegin, anchoredEnd, x, x0, w, _undamped);
                runner.Run(_batchPass, chunks);
                continue;
            }

            if (_undamped)
            {
                ProjectUndampedPairs(pairs, pairBegin, pairEnd, x, w);
            }
            else
            {
                ProjectPairs(pairs, pairBegin, pairEnd, x, x0, w);
            }

            ProjectAnchored(anchored, anchoredBegin, anchoredEnd, x, x0, w);
        }
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
            var numerator = (p->Stiffness * (l - p->RestLength)) + (p->Damping * moved);
            var denominator = ((p->Stiffness + p->Damping) * wsum) + 1.0;
            var dlambda = denominator <= double.MaxValue && Math.Abs(numerator) <= double.MaxValue
                ? -numerator / denominator
                : StiffLimit(p->Stiffness, p->Damping, l - p->RestLength, moved, wsum);
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

    /// <summary>
    /// <see cref="ProjectPairs"/> for springs without damping (c h = 0): dlambda = -k h^2 C / (k h^2 w + 1), without
    /// reading the start positions.
    /// </summary>
    private static unsafe void ProjectUndampedPairs(PairSpring* springs, int begin, int end, double* x, double* w)
    {
        for (PairSpring* p = springs + begin, last = springs + end; p < last; p++)
        {
            uint a = p->First, b = p->Second;
            double wi = w[a], wj = w[b];
            var wsum = wi + wj;
            if (wsum == 0.0)
            {
                continue;
            }

            double* xi = x + (3L * a), xj = x + (3L * b);
            double xi0 = xi[0], xi1 = xi[1], xi2 = xi[2], xj0 = xj[0], xj1 = xj[1], xj2 = xj[2];
            double dx = xi0 - xj0, dy = xi1 - xj1, dz = xi2 - xj2;
            var squared = (dx * dx) + (dy * dy) + (dz * dz);
            if (squared == 0.0)
            {
                continue;
            }

            var l = Math.Sqrt(squared);
            var inverse = 1.0 / l;
            double ux = dx * inverse, uy = dy * inverse, uz = dz * inverse;
            var numerator = p->Stiffness * (l - p->RestLength);
            var denominator = (p->Stiffness * wsum) + 1.0;
            var dlambda = denominator <= double.MaxValue && Math.Abs(numerator) <= double.MaxValue
                ? -numerator / denominator
                : StiffLimit(p->Stiffness, 0.0, l - p->RestLength, 0.0, wsum);
            double cx = dlambda * ux, cy = dlambda * uy, cz = dlambda * uz;
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
            var numerator = (p->Stiffness * (l - p->RestLength)) + (p->Damping * moved);
            var denominator = ((p->Stiffness + p->Damping) * wi) + 1.0;
            var dlambda = denominator <= double.MaxValue && Math.Abs(numerator) <= double.MaxValue
                ? -numerator / denominator
                : StiffLimit(p->Stiffness, p->Damping, l - p->RestLength, moved, wi);
            x[i] += wi * (dlambda * ux);
            x[i + 1] += wi * (dlambda * uy);
            x[i + 2] += wi * (dlambda * uz);
        }
    }

    /// <summary>
    /// dlambda where the usual form's numerator or denominator overflows (a stiffness near double.MaxValue on a light
    /// particle: (k h^2 + c h) w = infinity would make the correction 0, and the spring let its particle fall). Dividing
    /// through by s = k h^2 + c h gives the same value in terms that stay finite:
    /// dlambda = -(a C + b u . dx) / (w + 1 / s), a = k h^2 / s, b = c h / s (a + b = 1),
    /// which tends to the rigid projection -C / w as k grows. Where s itself overflows, 1 / s is taken as 0 (below the
    /// rounding of w for any mass under 1e292 kg) and a, b from halves of the two terms; a term that is infinite itself
    /// (a substep longer than 1e154 s) takes the whole, two of them half each.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining)]
    private static double StiffLimit(double stiffness, double damping, double violation, double moved, double w)
    {
        double a, b, inverse;
        var s = stiffness + damping;
        if (s <= double.MaxValue)
        {
            (a, b, inverse) = (stiffness / s, damping / s, 1.0 / s);
        }
        else
        {
            double halfStiffness = 0.5 * stiffness, halfDamping = 0.5 * damping;
            var half = halfStiffness + halfDamping;
            inverse = 0.0;
            if (half <= double.MaxValue)
            {
                (a, b) = (halfStiffness / half, halfDamping / half);
            }
            else if (double.IsInfinity(stiffness) && double.IsInfinity(damping))
            {
                (a, b) = (0.5, 0.5);
            }
            else
            {
                (a, b) = double.IsInfinity(stiffness) ? (1.0, 0.0) : (0.0, 1.0);
            }
        }

        return -((a * violation) + (b * moved)) / (w + inverse);
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
}
