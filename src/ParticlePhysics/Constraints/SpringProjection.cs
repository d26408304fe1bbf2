using System;
using System.Runtime.InteropServices;

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
/// </para>
/// </remarks>
public sealed class SpringProjection : IForceProjection
{
    private readonly ISpringElements _springs;
    private int _topologyVersion = -1;
    private int _parameterVersion = -1;
    private int _particles = -1;
    private int _count;

    // In colour order: ends (second -1 for an anchor), anchor point (3 per spring), k, L, c.
    private int[] _first = Array.Empty<int>();
    private int[] _second = Array.Empty<int>();
    private double[] _anchor = Array.Empty<double>();
    private double[] _stiffness = Array.Empty<double>();
    private double[] _restLength = Array.Empty<double>();
    private double[] _damping = Array.Empty<double>();
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

    /// <summary>The springs in the order they are projected (indices: the pair springs, then the anchored ones after them).</summary>
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
        var hh = h * h;
        unsafe
        {
            fixed (double* x = context.Positions, x0 = &MemoryMarshal.GetReference(context.StartPositions))
            fixed (double* w = &MemoryMarshal.GetReference(context.InverseMasses))
            fixed (double* anchor = _anchor, k = _stiffness, rest = _restLength, c = _damping)
            fixed (int* first = _first, second = _second)
            {
                for (var s = 0; s < _count; s++)
                {
                    long i = 3 * first[s];
                    var b = second[s];
                    var wi = w[first[s]];
                    var wj = b >= 0 ? w[b] : 0.0;
                    var wsum = wi + wj;
                    if (wsum == 0.0)
                    {
                        continue;
                    }

                    double dx, dy, dz, mx, my, mz;
                    if (b >= 0)
                    {
                        long j = 3L * b;
                        dx = x[i] - x[j];
                        dy = x[i + 1] - x[j + 1];
                        dz = x[i + 2] - x[j + 2];
                        mx = (x[i] - x0[i]) - (x[j] - x0[j]);
                        my = (x[i + 1] - x0[i + 1]) - (x[j + 1] - x0[j + 1]);
                        mz = (x[i + 2] - x0[i + 2]) - (x[j + 2] - x0[j + 2]);
                    }
                    else
                    {
                        var a = anchor + (3L * s);
                        dx = x[i] - a[0];
                        dy = x[i + 1] - a[1];
                        dz = x[i + 2] - a[2];
                        mx = x[i] - x0[i];
                        my = x[i + 1] - x0[i + 1];
                        mz = x[i + 2] - x0[i + 2];
                    }

                    var squared = (dx * dx) + (dy * dy) + (dz * dz);
                    if (squared == 0.0)
                    {
                        continue; // no direction, as the force is zero there
                    }

                    var l = Math.Sqrt(squared);
                    var inverse = 1.0 / l;
                    double ux = dx * inverse, uy = dy * inverse, uz = dz * inverse;
                    var stiff = k[s] * hh;
                    var damp = c[s] * h;
                    var moved = (ux * mx) + (uy * my) + (uz * mz);
                    var dlambda = -((stiff * (l - rest[s])) + (damp * moved)) / (((stiff + damp) * wsum) + 1.0);
                    double cx = dlambda * ux, cy = dlambda * uy, cz = dlambda * uz;
                    x[i] += wi * cx;
                    x[i + 1] += wi * cy;
                    x[i + 2] += wi * cz;
                    if (b >= 0)
                    {
                        long j = 3L * b;
                        x[j] -= wj * cx;
                        x[j + 1] -= wj * cy;
                        x[j + 2] -= wj * cz;
                    }
                }
            }
        }
    }

    /// <inheritdoc />
    /// <remarks>Nothing: the damping is in the projection.</remarks>
    public void SolveVelocities(in ConstraintContext context)
    {
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
            _first = new int[count];
            _second = new int[count];
            _anchor = new double[3 * count];
            _stiffness = new double[count];
            _restLength = new double[count];
            _damping = new double[count];
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
            // Colour the springs in their own index order: pairs, then anchored (second end -1).
            var first = new int[count];
            var second = new int[count];
            _pairFirst.AsSpan().CopyTo(first);
            _pairSecond.AsSpan().CopyTo(second);
            for (var a = 0; a < anchored; a++)
            {
                first[pairs + a] = _anchoredParticle[a];
                second[pairs + a] = -1;
            }

            _colourStarts = ConstraintColouring.Colour(first, second, count, particles, _order);
        }

        for (var s = 0; s < count; s++)
        {
            var source = _order[s];
            if (source < pairs)
            {
                _first[s] = _pairFirst[source];
                _second[s] = _pairSecond[source];
                _anchor[3 * s] = _anchor[(3 * s) + 1] = _anchor[(3 * s) + 2] = 0.0;
                _stiffness[s] = _pairParameters[3 * source];
                _restLength[s] = _pairParameters[(3 * source) + 1];
                _damping[s] = _pairParameters[(3 * source) + 2];
            }
            else
            {
                var a = source - pairs;
                _first[s] = _anchoredParticle[a];
                _second[s] = -1;
                _anchor[3 * s] = _anchoredParameters[6 * a];
                _anchor[(3 * s) + 1] = _anchoredParameters[(6 * a) + 1];
                _anchor[(3 * s) + 2] = _anchoredParameters[(6 * a) + 2];
                _stiffness[s] = _anchoredParameters[(6 * a) + 3];
                _restLength[s] = _anchoredParameters[(6 * a) + 4];
                _damping[s] = _anchoredParameters[(6 * a) + 5];
            }
        }

        _count = count;
        _particles = particles;
        _topologyVersion = topology;
        _parameterVersion = parameters;
    }
}
