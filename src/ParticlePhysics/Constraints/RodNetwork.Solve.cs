using System;

namespace ParticlePhysics.Constraints;

// The system J W J^T lambda = rhs that the forces and the projections solve: its rows (the gradients), the active
// links, the choice of solver, and W J^T lambda applied.
public sealed partial class RodNetwork
{
    // Per solve: J's rows (the gradients, 3 per link), the right-hand side, the multipliers, the links in the solve.
    private double[] _gradient = Array.Empty<double>();
    private double[] _rhs = Array.Empty<double>();
    private double[] _lambda = Array.Empty<double>();
    private bool[] _active = Array.Empty<bool>();

    private void SetGradient(int r, double gx, double gy, double gz)
    {
        _gradient[3 * r] = gx;
        _gradient[(3 * r) + 1] = gy;
        _gradient[(3 * r) + 2] = gz;
    }

    /// <summary>Solves for the active links, then drops the cables whose multiplier would push (positive) and solves again.</summary>
    private void SolveWithPullingCables(Span<double> w)
    {
        for (var attempt = 0; attempt <= _cableCount; attempt++)
        {
            Solve(w);
            var dropped = false;
            for (var r = 0; r < _count; r++)
            {
                if (_cable[r] && _active[r] && _lambda[r] > 0.0)
                {
                    _active[r] = false;
                    dropped = true;
                }
            }

            if (!dropped)
            {
                return;
            }
        }
    }

    /// <summary>
    /// Solves (J W J^T) lambda = rhs over the active links (the others get lambda = 0), with J's rows the gradients:
    /// +g_r at the first end, -g_r at the second.
    /// </summary>
    private void Solve(Span<double> w)
    {
        if (_bandwidth <= MaxDirectBandwidth)
        {
            SolveBanded(w);
        }
        else
        {
            SolveConjugateGradients(w);
        }
    }

    /// <summary>Adds W J^T lambda into <paramref name="target"/> (positions or velocities, 3 values per particle).</summary>
    private void ApplyCorrection(Span<double> w, Span<double> target)
    {
        for (var r = 0; r < _count; r++)
        {
            var lambda = _lambda[r];
            if (!_active[r] || lambda == 0.0)
            {
                continue;
            }

            int i = 3 * _first[r], j = 3 * _second[r], g = 3 * r;
            var si = lambda * w[_first[r]];
            target[i] += si * _gradient[g];
            target[i + 1] += si * _gradient[g + 1];
            target[i + 2] += si * _gradient[g + 2];
            if (j >= 0)
            {
                var sj = lambda * w[_second[r]];
                target[j] -= sj * _gradient[g];
                target[j + 1] -= sj * _gradient[g + 1];
                target[j + 2] -= sj * _gradient[g + 2];
            }
        }
    }

    private double DiagonalEntry(Span<double> w, int r)
    {
        var squared = GradientDot(r, r);
        var sum = w[_first[r]];
        if (_second[r] >= 0)
        {
            sum += w[_second[r]];
        }

        return sum * squared;
    }

    private double GradientDot(int r, int s) =>
        (_gradient[3 * r] * _gradient[3 * s]) + (_gradient[(3 * r) + 1] * _gradient[(3 * s) + 1])
        + (_gradient[(3 * r) + 2] * _gradient[(3 * s) + 2]);

    private double Sign(int r, int particle) => _first[r] == particle ? 1.0 : -1.0;
}
