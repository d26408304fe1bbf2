using System;

namespace ParticlePhysics.Constraints;

// The links' topology, rebuilt when links or particles are added: links by particle, the colour order, the band of
// J W J^T, and every per-link buffer sized to it, so that no evaluation allocates.
public sealed partial class RodNetwork
{
    // Rebuilt when links are added or the world's particle count changes: links by particle, colour order, the band
    // of J W J^T.
    private bool _topologyStale = true;
    private int _particles = -1;
    private int[] _linksStart = Array.Empty<int>();
    private int[] _links = Array.Empty<int>();
    private int[] _order = Array.Empty<int>();
    private int[] _colourStarts = { 0 };
    private int _bandwidth;

    /// <summary>Rebuilds the links by particle, the colour order and the band of J W J^T when links or particles changed.</summary>
    private void EnsureTopology(int particles)
    {
        if (!_topologyStale && particles == _particles)
        {
            return;
        }

        if (particles < _world.Count)
        {
            throw new ArgumentException(
                $"RodNetwork needs the {_world.Count} particles of its world; the buffers hold {particles}.");
        }

        var n = _count;
        var start = new int[particles + 1];
        for (var r = 0; r < n; r++)
        {
            start[_first[r] + 1]++;
            if (_second[r] >= 0)
            {
                start[_second[r] + 1]++;
            }
        }

        for (var p = 0; p < particles; p++)
        {
            start[p + 1] += start[p];
        }

        var fill = new int[particles];
        var links = new int[start[particles]];
        var bandwidth = 0;
        for (var r = 0; r < n; r++)
        {
            links[start[_first[r]] + fill[_first[r]]++] = r;
            if (_second[r] >= 0)
            {
                links[start[_second[r]] + fill[_second[r]]++] = r;
            }
        }

        for (var p = 0; p < particles; p++)
        {
            if (start[p + 1] > start[p])
            {
                // Links are listed in increasing index at each particle: the band is last minus first.
                bandwidth = Math.Max(bandwidth, links[start[p + 1] - 1] - links[start[p]]);
            }
        }

        _linksStart = start;
        _links = links;
        _bandwidth = bandwidth;
        _order = new int[n];
        _colourStarts = ConstraintColouring.Colour(_first, _second, n, particles, _order);
        _gradient = new double[3 * n];
        _rhs = new double[n];
        _lambda = new double[n];

        // The tensions of the links there were stay what the last evaluation found (a rebuild because particles were
        // added, or links, changes none of them); new links read 0 until evaluated.
        var tension = new double[n];
        _tension.AsSpan(0, Math.Min(_tension.Length, n)).CopyTo(tension);
        _tension = tension;
        _active = new bool[n];
        _kick = new double[n];
        _kickStep = new double[n];
        _geometric = new double[n];
        _linearizedLinks = -1;
        if (bandwidth <= MaxDirectBandwidth)
        {
            _band = new double[n * (bandwidth + 1)];
        }
        else
        {
            _residual = new double[n];
            _direction = new double[n];
            _product = new double[n];
            _preconditioned = new double[n];
            _diagonal = new double[n];
            _perParticle = new double[3 * particles];
        }

        _particles = particles;
        _topologyStale = false;
    }
}
