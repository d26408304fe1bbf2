using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Constraints;

// J W J^T of a chain (constraints coupled only to near indices): assembled as a band and factorised directly.
public sealed partial class RodNetwork
{
    private double[] _band = Array.Empty<double>();

    private void SolveBanded(Span<double> w)
    {
        var b = _bandwidth;
        var stride = b + 1;
        var band = _band.AsSpan(0, _count * stride);
        band.Clear();
        for (var r = 0; r < _count; r++)
        {
            _lambda[r] = _active[r] ? _rhs[r] : 0.0;
            band[(r * stride) + b] = _active[r] ? DiagonalEntry(w, r) : 1.0;
            if (_active[r] && band[(r * stride) + b] == 0.0)
            {
                // Both ends immovable or no direction: nothing this link can do.
                _active[r] = false;
                band[(r * stride) + b] = 1.0;
                _lambda[r] = 0.0;
            }
        }

        // Off-diagonal entries: two active links meeting at a free particle p couple by w_p (s_r g_r) . (s_s g_s).
        for (var p = 0; p < _particles; p++)
        {
            var wp = w[p];
            if (wp == 0.0)
            {
                continue;
            }

            for (var a = _linksStart[p]; a < _linksStart[p + 1]; a++)
            {
                var r = _links[a];
                if (!_active[r])
                {
                    continue;
                }

                for (var c = a + 1; c < _linksStart[p + 1]; c++)
                {
                    var s = _links[c];
                    if (!_active[s] || s == r)
                    {
                        continue;
                    }

                    int hi = Math.Max(r, s), lo = Math.Min(r, s);
                    band[(hi * stride) + b - (hi - lo)] += wp * Sign(r, p) * Sign(s, p) * GradientDot(r, s);
                }
            }
        }

        BandedCholesky.Factor(band, _count, b);
        BandedCholesky.Solve(band, _count, b, _lambda.AsSpan(0, _count));
    }
}
