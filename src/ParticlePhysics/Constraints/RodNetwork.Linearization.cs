using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Constraints;

// Implicit Euler's view of the tensions (IForceJacobian): their geometric stiffness, a zero-length spring per rod.
public sealed partial class RodNetwork
{
    // The implicit step's linearisation (IForceJacobian): a h^2 times each link's tension per unit length, and the
    // number of links it covers (-1 before the first).
    private double[] _geometric = Array.Empty<double>();
    private int _linearizedLinks = -1;

    /// <inheritdoc />
    /// <remarks>
    /// The geometric stiffness of the tensions of the last <see cref="AddConstraintForces"/>, which the world runs at the
    /// same state just before (Tournier et al., "Stable Constrained Dynamics", 2015). The force lambda d on end i
    /// (d = x_i - x_j, lambda &lt; 0 pulling) changes with the ends' positions, at fixed lambda, by
    /// d(lambda d) / dx_i = lambda I: a zero-length spring of stiffness k = -lambda = T / |d|, the tension per unit length.
    /// Why: an implicit step that sees the tension only as a force applies it along the start's direction while the rod
    /// turns, and that does work (on a chain under gravity the step is then semi-implicit Euler's, with its gain: see
    /// ProjectIntoTheKick). With this linearisation the step's tension acts along the end's direction,
    /// lambda_0 (x1_i - x1_j), where the velocities are tangent to the rods to O(h^2): the tension does no work to
    /// leading order, and implicit Euler dissipates |dv|_M^2 / 2 per step, as it does on any force. On a uniform
    /// rotation the step is backward Euler's on y' = i omega y: it turns by atan(h omega) and keeps
    /// 1 / sqrt(1 + (h omega)^2) of the speed. Left out:
    /// the derivatives of lambda itself (J^T dlambda / dx, along the rods, dense over a chain and not symmetric), which
    /// the projection after the step stands in for; and a rod that pushes (lambda &gt; 0), whose positive stiffness
    /// could make the implicit system indefinite, as springs clamp their compressed transverse stiffness. No velocity
    /// derivative: J = a K.
    /// </remarks>
    public void Linearize(
        in ParticleState state, double positionScale, double velocityScale, Span<double> positionJacobianTimesVelocity)
    {
        EnsureTopology(state.Count);
        var v = state.Velocities.ForReading();
        for (var r = 0; r < _count; r++)
        {
            var k = _lambda[r] < 0.0 ? -_lambda[r] : 0.0;
            _geometric[r] = positionScale * k;
            if (k == 0.0)
            {
                continue;
            }

            // (df/dx) v: -k (v_i - v_j) on end i, +k (v_i - v_j) on end j.
            int i = 3 * _first[r], j = 3 * _second[r];
            for (var c = 0; c < 3; c++)
            {
                var relative = j >= 0 ? v[i + c] - v[j + c] : v[i + c];
                positionJacobianTimesVelocity[i + c] -= k * relative;
                if (j >= 0)
                {
                    positionJacobianTimesVelocity[j + c] += k * relative;
                }
            }
        }

        _linearizedLinks = _count;
    }

    /// <inheritdoc />
    /// <exception cref="InvalidOperationException">No <see cref="Linearize"/> yet, or links were added since.</exception>
    public void AddJacobianProduct(ReadOnlySpan<double> w, Span<double> result)
    {
        CheckLinearized();
        var wr = w.ForReading();
        for (var r = 0; r < _count; r++)
        {
            var g = _geometric[r];
            if (g == 0.0)
            {
                continue;
            }

            int i = 3 * _first[r], j = 3 * _second[r];
            for (var c = 0; c < 3; c++)
            {
                var relative = j >= 0 ? wr[i + c] - wr[j + c] : wr[i + c];
                result[i + c] -= g * relative;
                if (j >= 0)
                {
                    result[j + c] += g * relative;
                }
            }
        }
    }

    /// <inheritdoc />
    /// <exception cref="InvalidOperationException">No <see cref="Linearize"/> yet, or links were added since.</exception>
    public void AddDiagonalBlocks(Span<double> blocks)
    {
        CheckLinearized();
        for (var r = 0; r < _count; r++)
        {
            var g = _geometric[r];
            if (g == 0.0)
            {
                continue;
            }

            AddIsotropic(blocks, _first[r], -g);
            if (_second[r] >= 0)
            {
                AddIsotropic(blocks, _second[r], -g);
            }
        }
    }

    /// <summary>Adds s I to the 3 x 3 block of <paramref name="particle"/> (9 values per particle, row-major).</summary>
    private static void AddIsotropic(Span<double> blocks, int particle, double s)
    {
        var o = 9 * particle;
        blocks[o] += s;
        blocks[o + 4] += s;
        blocks[o + 8] += s;
    }

    private void CheckLinearized()
    {
        if (_linearizedLinks != _count || _topologyStale)
        {
            throw new InvalidOperationException(_linearizedLinks < 0
                ? "The rods' Jacobian products and blocks need a Linearize first."
                : "Rods or cables were added since the last Linearize: linearise again.");
        }
    }
}
