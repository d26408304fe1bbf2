using System;

namespace ParticlePhysics.Fluids;

// The projection of the density constraints (Macklin and Müller 2013, section 3, for particles of any masses): each
// iteration evaluates every pair's kernel and gradient at the gathered positions, sums the densities and the
// constraint gradients over the pairs, takes each particle's lambda, and moves every particle at once (Jacobi), so the
// result does not depend on the order of the particles.
public sealed partial class PositionBasedFluid
{
    private void ProjectDensities(in ConstraintContext context)
    {
        if (_count == 0)
        {
            return;
        }

        for (var iteration = 0; iteration < _iterations; iteration++)
        {
            EvaluatePairs();
            SumDensities();
            TakeLambdas();
            MoveParticles();
        }

        var positions = context.Positions;
        for (var k = 0; k < _count; k++)
        {
            if (_inverse[k] == 0.0)
            {
                continue;
            }

            var p = 3 * _particles[k];
            positions[p] = _x[3 * k];
            positions[p + 1] = _x[(3 * k) + 1];
            positions[p + 2] = _x[(3 * k) + 2];
        }
    }

    // rho_a = kappa (m_a W(0) + sum_b m_b W_ab); grad_a C_a = (kappa / rho_0) sum_b m_b grad_a W_ab, and
    // sum_b w_b |grad_b C_a|^2 = (kappa / rho_0)^2 sum_b w_b m_b^2 |grad_a W_ab|^2 (kept without the factor).
    private void SumDensities()
    {
        var peak = _kernel.Peak;
        for (var k = 0; k < _count; k++)
        {
            _density[k] = _mass[k] * peak;
            _squares[k] = 0.0;
            _gradient[3 * k] = 0.0;
            _gradient[(3 * k) + 1] = 0.0;
            _gradient[(3 * k) + 2] = 0.0;
        }

        for (var q = 0; q < _pairs; q++)
        {
            int i = _first[q], j = _second[q];
            double gx = _pairGradient[3 * q], gy = _pairGradient[(3 * q) + 1], gz = _pairGradient[(3 * q) + 2];
            var g2 = (gx * gx) + (gy * gy) + (gz * gz);
            double mi = _mass[i], mj = _mass[j];
            _density[i] += mj * _pairKernel[q];
            _density[j] += mi * _pairKernel[q];
            _squares[i] += _inverse[j] * mj * mj * g2;
            _squares[j] += _inverse[i] * mi * mi * g2;
            _gradient[3 * i] += mj * gx;
            _gradient[(3 * i) + 1] += mj * gy;
            _gradient[(3 * i) + 2] += mj * gz;
            _gradient[3 * j] -= mi * gx;
            _gradient[(3 * j) + 1] -= mi * gy;
            _gradient[(3 * j) + 2] -= mi * gz;
        }

        SumWalls();
        for (var k = 0; k < _count; k++)
        {
            _density[k] *= _kappa;
        }
    }

    // lambda_a = -C_a / (sum_k w_k |grad_k C_a|^2 + epsilon D_0), with C_a = max(rho_a / rho_0 - 1, 0).
    private void TakeLambdas()
    {
        var scale = _kappa / RestDensity;
        var scale2 = scale * scale;
        var relaxation = _relaxation * _restDenominator;
        for (var k = 0; k < _count; k++)
        {
            var c = (_density[k] / RestDensity) - 1.0;
            if (!(c > 0.0))
            {
                _lambda[k] = 0.0;
                continue;
            }

            double gx = _gradient[3 * k], gy = _gradient[(3 * k) + 1], gz = _gradient[(3 * k) + 2];
            var denominator = (scale2 * ((_inverse[k] * ((gx * gx) + (gy * gy) + (gz * gz))) + _squares[k])) + relaxation;
            _lambda[k] = denominator > 0.0 ? -c / denominator : 0.0;
        }
    }

    // dx_a = w_a (kappa / rho_0) sum_b X_ab grad_a W_ab and dx_b = -w_b (kappa / rho_0) X_ab grad_a W_ab, with the
    // pair's weight X_ab = lambda_a m_b + lambda_b m_a + s_corr (m_a + m_b) / 2, s_corr = -k (W_ab / W(dq))^4 / D_0.
    private void MoveParticles()
    {
        _move.AsSpan(0, 3 * _count).Clear();
        var scale = _kappa / RestDensity;
        var pressure = _artificialPressure / _restDenominator;
        var peak = 1.0 / _pressurePeak;
        for (var q = 0; q < _pairs; q++)
        {
            int i = _first[q], j = _second[q];
            double mi = _mass[i], mj = _mass[j];
            var ratio = _pairKernel[q] * peak;
            var ratio2 = ratio * ratio;
            var correction = -pressure * ratio2 * ratio2;
            var weight = scale * ((_lambda[i] * mj) + (_lambda[j] * mi) + (0.5 * correction * (mi + mj)));
            if (weight == 0.0)
            {
                continue;
            }

            double gx = weight * _pairGradient[3 * q], gy = weight * _pairGradient[(3 * q) + 1], gz = weight * _pairGradient[(3 * q) + 2];
            double wi = _inverse[i], wj = _inverse[j];
            _move[3 * i] += wi * gx;
            _move[(3 * i) + 1] += wi * gy;
            _move[(3 * i) + 2] += wi * gz;
            _move[3 * j] -= wj * gx;
            _move[(3 * j) + 1] -= wj * gy;
            _move[(3 * j) + 2] -= wj * gz;
        }

        MoveByWalls();
        for (var k = 0; k < 3 * _count; k++)
        {
            _x[k] += _move[k];
        }
    }

    // Under a force-based integrator the projection's move dx of a particle changes its end velocity by dx / dt.
    private void ChangeVelocitiesByMoves(in ConstraintContext context)
    {
        var velocities = context.Velocities;
        var rate = 1.0 / context.Dt;
        for (var k = 0; k < _count; k++)
        {
            if (_inverse[k] == 0.0)
            {
                continue;
            }

            var p = 3 * _particles[k];
            for (var a = 0; a < 3; a++)
            {
                velocities[p + a] += (_x[(3 * k) + a] - _saved[(3 * k) + a]) * rate;
            }
        }
    }
}
