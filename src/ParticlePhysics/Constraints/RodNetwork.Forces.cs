using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Constraints;

// The constraint forces of the force-based integrators (Witkin and Baraff): J W J^T lambda = -J' q' - J W Q - ks C - kd C'.
public sealed partial class RodNetwork
{
    /// <inheritdoc />
    public void AddConstraintForces(in ParticleState state, Span<double> forces)
    {
        if (_count == 0)
        {
            return;
        }

        EnsureTopology(state.Count);
        var x = state.Positions.ForReading();
        var v = state.Velocities.ForReading();
        var w = state.InverseMasses.ForReading();
        for (var r = 0; r < _count; r++)
        {
            int i = 3 * _first[r], j = 3 * _second[r];
            double dx, dy, dz, ex, ey, ez, qx, qy, qz;
            var wi = w[_first[r]];
            if (j >= 0)
            {
                var wj = w[_second[r]];
                dx = x[i] - x[j];
                dy = x[i + 1] - x[j + 1];
                dz = x[i + 2] - x[j + 2];
                ex = v[i] - v[j];
                ey = v[i + 1] - v[j + 1];
                ez = v[i + 2] - v[j + 2];
                qx = (wi * forces[i]) - (wj * forces[j]);
                qy = (wi * forces[i + 1]) - (wj * forces[j + 1]);
                qz = (wi * forces[i + 2]) - (wj * forces[j + 2]);
            }
            else
            {
                var a = 3 * r;
                dx = x[i] - _anchor[a];
                dy = x[i + 1] - _anchor[a + 1];
                dz = x[i + 2] - _anchor[a + 2];
                ex = v[i];
                ey = v[i + 1];
                ez = v[i + 2];
                qx = wi * forces[i];
                qy = wi * forces[i + 1];
                qz = wi * forces[i + 2];
            }

            var squared = (dx * dx) + (dy * dy) + (dz * dz);
            var rate = (dx * ex) + (dy * ey) + (dz * ez);
            var length = _length[r];
            var active = squared > 0.0;
            if (active && _cable[r])
            {
                var l = Math.Sqrt(squared);
                active = l >= length * (1.0 - TautTolerance) && rate / l >= -TautTolerance * length;
            }

            SetGradient(r, dx, dy, dz);
            _active[r] = active;
            var value = 0.5 * (squared - (length * length));
            _rhs[r] = -((ex * ex) + (ey * ey) + (ez * ez)) - ((dx * qx) + (dy * qy) + (dz * qz))
                - (_driftStiffness * value) - (_driftDamping * rate);
        }

        SolveWithPullingCables(w);
        for (var r = 0; r < _count; r++)
        {
            var lambda = _lambda[r];
            var g = 3 * r;
            var length = Math.Sqrt((_gradient[g] * _gradient[g]) + (_gradient[g + 1] * _gradient[g + 1]) + (_gradient[g + 2] * _gradient[g + 2]));
            _tension[r] = -lambda * length;
            if (lambda == 0.0)
            {
                continue;
            }

            int i = 3 * _first[r], j = 3 * _second[r];
            double fx = lambda * _gradient[g], fy = lambda * _gradient[g + 1], fz = lambda * _gradient[g + 2];
            forces[i] += fx;
            forces[i + 1] += fy;
            forces[i + 2] += fz;
            if (j >= 0)
            {
                forces[j] -= fx;
                forces[j + 1] -= fy;
                forces[j + 2] -= fz;
            }
        }
    }
}
