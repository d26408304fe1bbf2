using System;

namespace ParticlePhysics.Constraints;

// J W J^T of a net (a band too wide to factorise): Jacobi-preconditioned conjugate gradients, matrix-free. Not a dense
// Cholesky (Numerics/DenseLinearSolver): the matrix has a few entries per row, so a product costs O(links) where a dense
// factorisation costs links^3 / 6 per evaluation, and a net with redundant rods (a singular J W J^T) needs no pivot floor.
public sealed partial class RodNetwork
{
    // Conjugate gradients stop at this relative residual, or after 2 n + 50 iterations (n links).
    private const double SolveTolerance = 1e-13;

    // The vectors of the iteration (one per link), and one 3-vector per particle for the product.
    private double[] _residual = Array.Empty<double>();
    private double[] _direction = Array.Empty<double>();
    private double[] _product = Array.Empty<double>();
    private double[] _preconditioned = Array.Empty<double>();
    private double[] _diagonal = Array.Empty<double>();
    private double[] _perParticle = Array.Empty<double>();

    private void SolveConjugateGradients(Span<double> w)
    {
        var n = _count;
        var rhsNorm = 0.0;
        for (var r = 0; r < n; r++)
        {
            var d = _active[r] ? DiagonalEntry(w, r) : 0.0;
            if (!(d > 0.0))
            {
                _active[r] = false;
                d = 1.0;
            }

            _diagonal[r] = d;
            _lambda[r] = 0.0;
            var rr = _active[r] ? _rhs[r] : 0.0;
            _residual[r] = rr;
            rhsNorm += rr * rr;
        }

        rhsNorm = Math.Sqrt(rhsNorm);
        if (rhsNorm == 0.0)
        {
            return;
        }

        var rz = 0.0;
        for (var r = 0; r < n; r++)
        {
            _preconditioned[r] = _residual[r] / _diagonal[r];
            _direction[r] = _preconditioned[r];
            rz += _residual[r] * _preconditioned[r];
        }

        var target = SolveTolerance * rhsNorm;
        var maxIterations = (2 * n) + 50;
        for (var iteration = 0; iteration < maxIterations; iteration++)
        {
            var pq = MultiplyActive(w, _direction, _product);
            if (!(pq > 0.0))
            {
                break;
            }

            var alpha = rz / pq;
            var residualNorm = 0.0;
            for (var r = 0; r < n; r++)
            {
                _lambda[r] += alpha * _direction[r];
                _residual[r] -= alpha * _product[r];
                residualNorm += _residual[r] * _residual[r];
            }

            if (Math.Sqrt(residualNorm) <= target)
            {
                break;
            }

            var rzNext = 0.0;
            for (var r = 0; r < n; r++)
            {
                _preconditioned[r] = _residual[r] / _diagonal[r];
                rzNext += _residual[r] * _preconditioned[r];
            }

            var beta = rzNext / rz;
            rz = rzNext;
            for (var r = 0; r < n; r++)
            {
                _direction[r] = _preconditioned[r] + (beta * _direction[r]);
            }
        }
    }

    /// <summary>y = (J W J^T) y_in over the active links (0 elsewhere); returns y_in . y.</summary>
    private double MultiplyActive(Span<double> w, double[] input, double[] output)
    {
        var sums = _perParticle.AsSpan(0, 3 * _particles);
        sums.Clear();
        for (var r = 0; r < _count; r++)
        {
            if (!_active[r])
            {
                continue;
            }

            int i = 3 * _first[r], j = 3 * _second[r], g = 3 * r;
            var y = input[r];
            sums[i] += y * _gradient[g];
            sums[i + 1] += y * _gradient[g + 1];
            sums[i + 2] += y * _gradient[g + 2];
            if (j >= 0)
            {
                sums[j] -= y * _gradient[g];
                sums[j + 1] -= y * _gradient[g + 1];
                sums[j + 2] -= y * _gradient[g + 2];
            }
        }

        var dot = 0.0;
        for (var r = 0; r < _count; r++)
        {
            if (!_active[r])
            {
                output[r] = 0.0;
                continue;
            }

            int i = 3 * _first[r], j = 3 * _second[r], g = 3 * r;
            var wi = w[_first[r]];
            var value = wi * ((_gradient[g] * sums[i]) + (_gradient[g + 1] * sums[i + 1]) + (_gradient[g + 2] * sums[i + 2]));
            if (j >= 0)
            {
                var wj = w[_second[r]];
                value -= wj * ((_gradient[g] * sums[j]) + (_gradient[g + 1] * sums[j + 1]) + (_gradient[g + 2] * sums[j + 2]));
            }

            output[r] = value;
            dot += input[r] * value;
        }

        return dot;
    }
}
