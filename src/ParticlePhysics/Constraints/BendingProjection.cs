using System;
using ParticlePhysics.Numerics;

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
    private readonly IBendingElements _bending;
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
        Span<double> c = stackalloc double[3 * Components];
        for (var e = 0; e < _stiffness.Length; e++)
        {
            var sh = _scaled[e];
            if (sh == 0.0)
            {
                continue;
            }

            var slot = Slots * e;
            var weight = Slots * Components * e;

            // B = sum_v w_v b_v b_v^T and c_k = sum_v b_kv x_v, each coordinate.
            double b11 = 0, b12 = 0, b13 = 0, b22 = 0, b23 = 0, b33 = 0;
            c.Clear();
            var free = false;
            for (var v = 0; v < Slots; v++)
            {
                var particle = _slots[slot + v];
                if (particle < 0)
                {
                    break;
                }

                double k1 = _weights[weight + v], k2 = _weights[weight + Slots + v], k3 = _weights[weight + (2 * Slots) + v];
                var o = 3 * particle;
                double px = x[o], py = x[o + 1], pz = x[o + 2];
                c[0] += k1 * px;
                c[1] += k1 * py;
                c[2] += k1 * pz;
                c[3] += k2 * px;
                c[4] += k2 * py;
                c[5] += k2 * pz;
                c[6] += k3 * px;
                c[7] += k3 * py;
                c[8] += k3 * pz;
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
                continue;
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
                continue; // s h^2 B beyond the finite numbers: leave the element as it is rather than write infinities
            }

            var scale = -sh / det;
            for (var d = 0; d < 3; d++)
            {
                double r1 = c[d], r2 = c[3 + d], r3 = c[6 + d];
                c[d] = scale * ((k11 * r1) + (k12 * r2) + (k13 * r3));
                c[3 + d] = scale * ((k12 * r1) + (k22 * r2) + (k23 * r3));
                c[6 + d] = scale * ((k13 * r1) + (k23 * r2) + (k33 * r3));
            }

            for (var v = 0; v < Slots; v++)
            {
                var particle = _slots[slot + v];
                if (particle < 0)
                {
                    break;
                }

                var wv = w[particle];
                if (wv == 0.0)
                {
                    continue;
                }

                double k1 = wv * _weights[weight + v], k2 = wv * _weights[weight + Slots + v], k3 = wv * _weights[weight + (2 * Slots) + v];
                var o = 3 * particle;
                x[o] += (k1 * c[0]) + (k2 * c[3]) + (k3 * c[6]);
                x[o + 1] += (k1 * c[1]) + (k2 * c[4]) + (k3 * c[7]);
                x[o + 2] += (k1 * c[2]) + (k2 * c[5]) + (k3 * c[8]);
            }
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
