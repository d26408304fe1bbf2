using System;

namespace ParticlePhysics.Fluids;

// The velocity passes after each substep's positions: XSPH viscosity and vorticity confinement, both from the
// velocities as the substep left them (Jacobi), at the positions the other sets (contacts) left.
public sealed partial class PositionBasedFluid
{
    private const double ViscosityPeriod = 1.0 / 60.0;

    private void CorrectVelocities(in ConstraintContext context)
    {
        if (_count == 0 || (_viscosity == 0.0 && _vorticity == 0.0))
        {
            return;
        }

        var positions = context.Positions;
        var velocities = context.Velocities;
        for (var k = 0; k < _count; k++)
        {
            var p = 3 * _particles[k];
            for (var a = 0; a < 3; a++)
            {
                _x[(3 * k) + a] = positions[p + a];
                _v[(3 * k) + a] = velocities[p + a];
            }
        }

        EvaluatePairs();
        _move.AsSpan(0, 3 * _count).Clear();
        if (_viscosity > 0.0)
        {
            AddViscosity(_viscosity * context.Dt / ViscosityPeriod);
        }

        if (_vorticity > 0.0)
        {
            AddVorticityConfinement(context.Dt);
        }

        for (var k = 0; k < _count; k++)
        {
            if (_inverse[k] == 0.0)
            {
                continue;
            }

            var p = 3 * _particles[k];
            velocities[p] += _move[3 * k];
            velocities[p + 1] += _move[(3 * k) + 1];
            velocities[p + 2] += _move[(3 * k) + 2];
        }
    }

    // XSPH: dv_a = c (kappa / rho_0) sum_b m_b W_ab (v_b - v_a), so that m_a dv_a + m_b dv_b = 0 for each pair.
    private void AddViscosity(double c)
    {
        var scale = c * _kappa / RestDensity;
        for (var q = 0; q < _pairs; q++)
        {
            int i = _first[q], j = _second[q];
            var w = scale * _pairKernel[q];
            double wi = w * _mass[j], wj = w * _mass[i];
            for (var a = 0; a < 3; a++)
            {
                var dv = _v[(3 * j) + a] - _v[(3 * i) + a];
                _move[(3 * i) + a] += wi * dv;
                _move[(3 * j) + a] -= wj * dv;
            }
        }
    }

    // omega_a = sum_b V_b grad_a W_ab x (v_b - v_a) (the SPH curl, V_b = kappa m_b / rho_0), eta_a = sum_b V_b
    // (|omega_b| - |omega_a|) grad_a W_ab (the gradient of |omega|), N = eta / |eta|, and the acceleration
    // epsilon h |omega| (N x omega).
    private void AddVorticityConfinement(double dt)
    {
        var volume = _kappa / RestDensity;
        _omega.AsSpan(0, 3 * _count).Clear();
        for (var q = 0; q < _pairs; q++)
        {
            int i = _first[q], j = _second[q];
            double gx = _pairGradient[3 * q], gy = _pairGradient[(3 * q) + 1], gz = _pairGradient[(3 * q) + 2];
            double ux = _v[3 * j] - _v[3 * i], uy = _v[(3 * j) + 1] - _v[(3 * i) + 1], uz = _v[(3 * j) + 2] - _v[(3 * i) + 2];
            double cx = (gy * uz) - (gz * uy), cy = (gz * ux) - (gx * uz), cz = (gx * uy) - (gy * ux);
            double vi = volume * _mass[j], vj = volume * _mass[i];
            _omega[3 * i] += vi * cx;
            _omega[(3 * i) + 1] += vi * cy;
            _omega[(3 * i) + 2] += vi * cz;
            _omega[3 * j] += vj * cx;
            _omega[(3 * j) + 1] += vj * cy;
            _omega[(3 * j) + 2] += vj * cz;
        }

        for (var k = 0; k < _count; k++)
        {
            double ox = _omega[3 * k], oy = _omega[(3 * k) + 1], oz = _omega[(3 * k) + 2];
            _omegaNorm[k] = Math.Sqrt((ox * ox) + (oy * oy) + (oz * oz));
            _gradient[3 * k] = 0.0;
            _gradient[(3 * k) + 1] = 0.0;
            _gradient[(3 * k) + 2] = 0.0;
        }

        for (var q = 0; q < _pairs; q++)
        {
            int i = _first[q], j = _second[q];
            var rise = _omegaNorm[j] - _omegaNorm[i];
            double si = volume * _mass[j] * rise, sj = volume * _mass[i] * rise;
            for (var a = 0; a < 3; a++)
            {
                var g = _pairGradient[(3 * q) + a];
                _gradient[(3 * i) + a] += si * g;
                _gradient[(3 * j) + a] += sj * g;
            }
        }

        var strength = _vorticity * _kernel.Radius * dt;
        for (var k = 0; k < _count; k++)
        {
            double ex = _gradient[3 * k], ey = _gradient[(3 * k) + 1], ez = _gradient[(3 * k) + 2];
            var length = Math.Sqrt((ex * ex) + (ey * ey) + (ez * ez));
            if (!(length > 0.0))
            {
                continue;
            }

            var s = strength * _omegaNorm[k] / length;
            double ox = _omega[3 * k], oy = _omega[(3 * k) + 1], oz = _omega[(3 * k) + 2];
            _move[3 * k] += s * ((ey * oz) - (ez * oy));
            _move[(3 * k) + 1] += s * ((ez * ox) - (ex * oz));
            _move[(3 * k) + 2] += s * ((ex * oy) - (ey * ox));
        }
    }
}
