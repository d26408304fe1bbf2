using System;
using ParticlePhysics.Numerics;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Constraints;

/// <summary>
/// The elements of a quadratic bending energy (<see cref="IBendingElements"/>: <c>Forces.QuadraticBending</c>) as XPBD
/// constraints under the position-based integrator: the world leaves the bending out of the forces and this set
/// projects each element once per substep. Under the force-based integrators it does nothing.
/// </summary>
/// <remarks>
/// <para>
/// Element e is the linear constraint c_k = sum_v b_kv x_v (k = 1 to 3 components, each a vector) of stiffness s
/// (energy s / 2 sum_k |c_k|^2), compliance alpha = 1 / s. Its gradient is b_kv times the identity, so the block system
/// of XPBD (Macklin et al. 2016) separates by coordinate with one 3 x 3 matrix B = sum_v w_v b_v b_v^T:
/// dlambda = -(B + I / (s h^2))^-1 c = -(s h^2 B + I)^-1 (s h^2 c) for each of x, y and z, then
/// x_v += w_v sum_k b_kv dlambda_k. The matrix s h^2 B + I is at least the identity, so the solve (by cofactors) never
/// fails, and as s h^2 grows the projection tends to the rigid one. A linear constraint projected once is exact for its
/// element alone; the elements are projected in colour order (<see cref="ElementColouring"/>).
/// </para>
/// </remarks>
public sealed class BendingProjection : IForceProjection
{
    private const int Slots = 6;
    private const int Components = 3;

    // Elements per chunk below which a runner is not worth waking.
    private const int MinElementsPerChunk = 64;
    private readonly IBendingElements _bending;
    private readonly ColourPass _pass = new();
    private int _topologyVersion = -1;
    private int _parameterVersion = -1;
    private int _particles = -1;
    private int[] _slots = Array.Empty<int>();
    private double[] _weights = Array.Empty<double>();
    private double[] _stiffness = Array.Empty<double>();
    private double[] _scaled = Array.Empty<double>();
    private int[] _colourStarts = { 0 };
    private double _preparedStep = double.NaN;

    /// <summary>The projection of <paramref name="bending"/>; add it to the world that holds it with <see cref="ParticleWorld.AddConstraints"/>.</summary>
    public BendingProjection(IBendingElements bending)
    {
        Guard.NotNull(bending, nameof(bending));
        _bending = bending;
    }

    /// <inheritdoc />
    public IForceGenerator Force => _bending;

    /// <summary>The number of colours of the elements' colouring: 0 before the first projection.</summary>
    public int ColourCount => _colourStarts.Length - 1;

    /// <inheritdoc />
    /// <remarks>Nothing: under the force-based integrators the bending acts as a force.</remarks>
    public void Resolve(in ConstraintContext context)
    {
    }

    /// <inheritdoc />
    /// <remarks>Nothing: the bending has no damping of its own.</remarks>
    public void SolveVelocities(in ConstraintContext context)
    {
    }

    /// <inheritdoc />
    public void Project(in ConstraintContext context)
    {
        Refresh(context.Count);
        var h = context.Dt;
        if (h != _preparedStep)
        {
            var hh = h * h;
            for (var e = 0; e < _stiffness.Length; e++)
            {
                _scaled[e] = _stiffness[e] * hh;
            }

            _preparedStep = h;
        }

        var x = context.Positions;
        var w = context.InverseMasses.ForReading();
        if (context.Runner is not { MaxParallelism: > 1 } runner)
        {
            ProjectRange(0, _stiffness.Length, x, w);
            return;
        }

        unsafe
        {
            // The spans hold the world's particles, and Refresh checked every slot against their count.
            fixed (double* px = x, pw = w)
            {
                for (var k = 0; k + 1 < _colourStarts.Length; k++)
                {
                    // The elements of a colour share no particle: split over the runner, the same bits in any order.
                    int begin = _colourStarts[k], end = _colourStarts[k + 1];
                    var chunks = Math.Min(2 * runner.MaxParallelism, (end - begin) / MinElementsPerChunk);
                    if (chunks > 1)
                    {
                        _pass.Set(this, begin, end, px, pw, x.Length, w.Length);
                        runner.Run(_pass, chunks);
                    }
                    else
                    {
                        ProjectRange(begin, end, x, w);
                    }
                }
            }
        }
    }

    private unsafe void ProjectRange(int begin, int end, Span<double> x, Span<double> w)
    {
        // Every slot was checked against the particle count in Refresh, and x and w hold that many particles: no
        // pointer below leaves its array. The nine components of c live in registers, not in a span.
        fixed (double* px = x, pw = w, weights = _weights)
        fixed (int* slots = _slots)
        {
            for (var e = begin; e < end; e++)
            {
                ProjectElement(slots + (Slots * e), weights + (Slots * Components * e), _scaled[e], px, pw);
            }
        }
    }

    private static unsafe void ProjectElement(int* slot, double* weight, double sh, double* x, double* w)
    {
        if (sh == 0.0)
        {
            return;
        }

        // B = sum_v w_v b_v b_v^T and c_k = sum_v b_kv x_v, each coordinate.
        double b11 = 0, b12 = 0, b13 = 0, b22 = 0, b23 = 0, b33 = 0;
        double c0 = 0, c1 = 0, c2 = 0, c3 = 0, c4 = 0, c5 = 0, c6 = 0, c7 = 0, c8 = 0;
        var free = false;
        for (var v = 0; v < Slots; v++)
        {
            var particle = slot[v];
            if (particle < 0)
            {
                break;
            }

            double k1 = weight[v], k2 = weight[Slots + v], k3 = weight[(2 * Slots) + v];
            var p = x + (3L * particle);
            double px = p[0], py = p[1], pz = p[2];
            c0 += k1 * px;
            c1 += k1 * py;
            c2 += k1 * pz;
            c3 += k2 * px;
            c4 += k2 * py;
            c5 += k2 * pz;
            c6 += k3 * px;
            c7 += k3 * py;
            c8 += k3 * pz;
            var wv = w[particle];
            if (wv != 0.0)
            {
                free = true;
                b11 += wv * k1 * k1;
                b12 += wv * k1 * k2;
                b13 += wv * k1 * k3;
                b22 += wv * k2 * k2;
                b23 += wv * k2 * k3;
                b33 += wv * k3 * k3;
            }
        }

        if (!free)
        {
            return;
        }

        // M = s h^2 B + I, solved by its cofactors for the three coordinates.
        double m11 = (sh * b11) + 1.0, m12 = sh * b12, m13 = sh * b13;
        double m22 = (sh * b22) + 1.0, m23 = sh * b23, m33 = (sh * b33) + 1.0;
        var k11 = (m22 * m33) - (m23 * m23);
        var k12 = (m13 * m23) - (m12 * m33);
        var k13 = (m12 * m23) - (m13 * m22);
        var k22 = (m11 * m33) - (m13 * m13);
        var k23 = (m12 * m13) - (m11 * m23);
        var k33 = (m11 * m22) - (m12 * m12);
        var det = (m11 * k11) + (m12 * k12) + (m13 * k13);
        if (!(det >= 1.0) || det > double.MaxValue)
        {
            return; // s h^2 B beyond the finite numbers: leave the element as it is rather than write infinities
        }

        var scale = -sh / det;
        double l0 = scale * ((k11 * c0) + (k12 * c3) + (k13 * c6)), l3 = scale * ((k12 * c0) + (k22 * c3) + (k23 * c6)), l6 = scale * ((k13 * c0) + (k23 * c3) + (k33 * c6));
        double l1 = scale * ((k11 * c1) + (k12 * c4) + (k13 * c7)), l4 = scale * ((k12 * c1) + (k22 * c4) + (k23 * c7)), l7 = scale * ((k13 * c1) + (k23 * c4) + (k33 * c7));
        double l2 = scale * ((k11 * c2) + (k12 * c5) + (k13 * c8)), l5 = scale * ((k12 * c2) + (k22 * c5) + (k23 * c8)), l8 = scale * ((k13 * c2) + (k23 * c5) + (k33 * c8));
        for (var v = 0; v < Slots; v++)
        {
            var particle = slot[v];
            if (particle < 0)
            {
                break;
            }

            var wv = w[particle];
            if (wv == 0.0)
            {
                continue;
            }

            double k1 = wv * weight[v], k2 = wv * weight[Slots + v], k3 = wv * weight[(2 * Slots) + v];
            var p = x + (3L * particle);
            p[0] += (k1 * l0) + (k2 * l3) + (k3 * l6);
            p[1] += (k1 * l1) + (k2 * l4) + (k3 * l7);
            p[2] += (k1 * l2) + (k2 * l5) + (k3 * l8);
        }
    }

    /// <summary>One colour over the runner's chunks: each chunk projects a range of its elements.</summary>
    private sealed unsafe class ColourPass : IParallelWork
    {
        private BendingProjection? _owner;
        private double* _x;
        private double* _w;
        private int _coordinates;
        private int _particles;
        private int _begin;
        private int _end;

        public void Set(BendingProjection owner, int begin, int end, double* x, double* w, int coordinates, int particles)
        {
            _owner = owner;
            _begin = begin;
            _end = end;
            _x = x;
            _w = w;
            _coordinates = coordinates;
            _particles = particles;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _end - _begin);
            _owner!.ProjectRange(_begin + begin, _begin + end, new Span<double>(_x, _coordinates), new Span<double>(_w, _particles));
        }
    }

    /// <summary>Recolours when the elements changed, and recopies their parameters when those changed.</summary>
    private void Refresh(int particles)
    {
        var topology = _bending.TopologyVersion;
        var parameters = _bending.ParameterVersion;
        if (topology == _topologyVersion && parameters == _parameterVersion && particles == _particles)
        {
            return;
        }

        var count = _bending.ElementCount;
        var slots = new int[Slots * count];
        var weights = new double[Slots * Components * count];
        var stiffness = new double[count];
        _bending.CopyElements(slots, weights, stiffness);
        for (var k = 0; k < slots.Length; k++)
        {
            if (slots[k] >= particles)
            {
                throw new ArgumentException($"Bending element {k / Slots} names particle {slots[k]}, but the world has {particles}.");
            }
        }

        var order = new int[count];
        _colourStarts = ElementColouring.Colour(slots, Slots, count, particles, order);
        _slots = new int[Slots * count];
        _weights = new double[Slots * Components * count];
        _stiffness = new double[count];
        _scaled = new double[count];
        for (var k = 0; k < count; k++)
        {
            var e = order[k];
            Array.Copy(slots, Slots * e, _slots, Slots * k, Slots);
            Array.Copy(weights, Slots * Components * e, _weights, Slots * Components * k, Slots * Components);
            _stiffness[k] = stiffness[e];
        }

        _preparedStep = double.NaN;
        _particles = particles;
        _topologyVersion = topology;
        _parameterVersion = parameters;
    }
}
