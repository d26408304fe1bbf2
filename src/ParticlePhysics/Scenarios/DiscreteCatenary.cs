using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Scenarios;

/// <summary>
/// The rest shape of a chain of N equal particles joined by N - 1 rods of length l, hanging between two pins at the
/// same height a span D apart: the discrete catenary.
/// </summary>
/// <remarks>
/// At rest each rod carries the same horizontal tension H (no horizontal force acts on a particle but the rods), and
/// the vertical tension grows by m g at each of the N - 2 free particles; by symmetry the middle of the chain carries
/// none, so rod j (from particle j to j + 1) has slope tan(phi_j) = (j - (N - 2) / 2) m g / H, j = 0 .. N - 2. H is
/// fixed by the span: the sum of l cos(phi_j) is D. With s = m g / H, f(s) = sum l / sqrt(1 + (a_j s)^2) - D
/// (a_j = j - (N - 2) / 2) falls from L - D &gt; 0 at s = 0 toward -D, so it has one root, found by safeguarded Newton.
/// The shape then follows rod by rod from the first pin: x(j + 1) = x(j) + l cos(phi_j), y(j + 1) = y(j) + l sin(phi_j).
/// </remarks>
public sealed class DiscreteCatenary
{
    private readonly double[] _positions;

    /// <summary>Solves the rest shape.</summary>
    /// <param name="particles">N, at least 3.</param>
    /// <param name="rodLength">l, in m.</param>
    /// <param name="span">D, in m: less than (N - 1) l.</param>
    /// <param name="particleMass">m, in kg.</param>
    /// <param name="gravity">g, in m/s^2: positive (without gravity a slack chain has no rest shape).</param>
    /// <param name="left">The first pin's position; the last is at left + (D, 0, 0).</param>
    public DiscreteCatenary(int particles, double rodLength, double span, double particleMass, double gravity, Vector3d left)
    {
        if (particles < 3)
        {
            throw new ArgumentOutOfRangeException(nameof(particles), particles, $"A hanging chain needs at least 3 particles; got {particles}.");
        }

        Guard.PositiveFinite(rodLength, nameof(rodLength));
        Guard.PositiveFinite(span, nameof(span));
        Guard.PositiveFinite(particleMass, nameof(particleMass));
        Guard.PositiveFinite(gravity, nameof(gravity), "Without gravity a slack chain has no rest shape.");
        var rods = particles - 1;
        if (!(span < rods * rodLength))
        {
            throw new ArgumentException(
                $"The span {Guard.Format(span)} m must be shorter than the chain, {Guard.Format(rods * rodLength)} m.", nameof(span));
        }

        var middle = 0.5 * (particles - 2);
        (double, double) Gap(double s)
        {
            double sum = -span, slope = 0;
            for (var j = 0; j < rods; j++)
            {
                var a = j - middle;
                var q = 1.0 + (a * a * s * s);
                var root = Math.Sqrt(q);
                sum += rodLength / root;
                slope -= rodLength * a * a * s / (q * root);
            }

            return (sum, slope);
        }

        var hi = 1.0;
        for (var doubling = 0; doubling < 2000 && Gap(hi).Item1 > 0.0; doubling++)
        {
            hi *= 2.0;
        }

        var slopeScale = SafeguardedNewton.Root(Gap, 0.0, hi);
        HorizontalTension = particleMass * gravity / slopeScale;
        _positions = new double[3 * particles];
        double x = left.X, y = left.Y;
        for (var j = 0; j <= rods; j++)
        {
            _positions[3 * j] = x;
            _positions[(3 * j) + 1] = y;
            _positions[(3 * j) + 2] = left.Z;
            if (j < rods)
            {
                var tangent = (j - middle) * slopeScale;
                var cos = 1.0 / Math.Sqrt(1.0 + (tangent * tangent));
                x += rodLength * cos;
                y += rodLength * tangent * cos;
            }
        }
    }

    /// <summary>H, the horizontal tension every rod carries at rest, in newtons.</summary>
    public double HorizontalTension { get; }

    /// <summary>The rest positions, 3 values per particle.</summary>
    public ReadOnlySpan<double> Positions => _positions;

    /// <summary>The largest distance of a particle of <paramref name="positions"/> (3 values per particle) from its rest position, in m.</summary>
    public double MaxDistance(ReadOnlySpan<double> positions)
    {
        var p = positions.ForReading();
        if (p.Length < _positions.Length)
        {
            throw new ArgumentException($"positions must hold {_positions.Length} values; got {p.Length}.", nameof(positions));
        }

        var worst = 0.0;
        for (var i = 0; i < _positions.Length; i += 3)
        {
            double dx = p[i] - _positions[i], dy = p[i + 1] - _positions[i + 1], dz = p[i + 2] - _positions[i + 2];
            worst = Math.Max(worst, Math.Sqrt((dx * dx) + (dy * dy) + (dz * dz)));
        }

        return worst;
    }
}
