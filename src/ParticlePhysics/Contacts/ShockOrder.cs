using System;

namespace ParticlePhysics.Contacts;

/// <summary>
/// The order of the separation's shock-propagation pass (Guendelman, Bridson and Fedkiw, "Nonconvex rigid bodies with
/// stacking", 2003): each particle's rank, the number of touching contacts between it and an obstacle (0 on an
/// obstacle or pinned), by breadth-first search; and the pairs sorted by the rank of their lower end, so that one pass
/// that holds the lower particle of each pair still carries the support up a whole stack.
/// </summary>
internal sealed class ShockOrder
{
    private const int Unranked = int.MaxValue;

    private int[] _rank = Array.Empty<int>();
    private int[] _frontier = Array.Empty<int>();
    private int[] _start = Array.Empty<int>();
    private int[] _ranked = Array.Empty<int>();
    private int[] _pairsNear = Array.Empty<int>();

    /// <summary>Particle <paramref name="i"/>'s rank from the last <see cref="Order"/>.</summary>
    public int Rank(int i) => _rank[i];

    /// <summary>The pair at place <paramref name="k"/> of the ranked order.</summary>
    public int PairAt(int k) => _ranked[k];

    /// <summary>
    /// Ranks the particles from the supports (pinned particles and those in <paramref name="near"/>) through the pairs
    /// that touch at <paramref name="x"/>, then orders the pairs by the rank of their lower end (a stable counting sort;
    /// unranked pairs last, in their own order).
    /// </summary>
    public void Order(
        int n, Span<int> first, Span<int> second, Span<double> inverseMasses, ObstacleContactList near,
        Span<double> x, Span<double> radii, double touchingMargin, int largestPairs)
    {
        var pairs = first.Length;
        if (_rank.Length < n)
        {
            _rank = new int[n];
            _frontier = new int[n];
            _start = new int[n + 2];
        }

        if (_ranked.Length < pairs)
        {
            _ranked = new int[Math.Max(pairs, (int)Math.Min(2L * _ranked.Length, largestPairs))];
            _pairsNear = new int[2 * _ranked.Length];
        }

        // Each particle's touching pairs (CSR), then ranks by breadth-first search from the supports.
        Array.Clear(_start, 0, n + 2);
        for (var p = 0; p < pairs; p++)
        {
            _start[first[p] + 2]++;
            _start[second[p] + 2]++;
        }

        for (var i = 0; i < n; i++)
        {
            _start[i + 2] += _start[i + 1];
        }

        for (var p = 0; p < pairs; p++)
        {
            _pairsNear[_start[first[p] + 1]++] = p;
            _pairsNear[_start[second[p] + 1]++] = p;
        }

        var head = 0;
        var tail = 0;
        for (var i = 0; i < n; i++)
        {
            _rank[i] = inverseMasses[i] == 0.0 ? 0 : Unranked;
            if (_rank[i] == 0)
            {
                _frontier[tail++] = i;
            }
        }

        for (var c = 0; c < near.Count; c++)
        {
            var i = near.Particle(c);
            if (_rank[i] != 0)
            {
                _rank[i] = 0;
                _frontier[tail++] = i;
            }
        }

        while (head < tail)
        {
            var i = _frontier[head++];
            for (var k = _start[i]; k < _start[i + 1]; k++)
            {
                var p = _pairsNear[k];
                var j = first[p] == i ? second[p] : first[p];
                if (_rank[j] == Unranked && Touching(x, i, j, radii, touchingMargin))
                {
                    _rank[j] = _rank[i] + 1;
                    _frontier[tail++] = j;
                }
            }
        }

        Array.Clear(_start, 0, n + 2);
        for (var p = 0; p < pairs; p++)
        {
            _start[Math.Min(LowerRank(first[p], second[p]), n) + 1]++;
        }

        for (var r = 0; r <= n; r++)
        {
            _start[r + 1] += _start[r];
        }

        for (var p = 0; p < pairs; p++)
        {
            _ranked[_start[Math.Min(LowerRank(first[p], second[p]), n)]++] = p;
        }
    }

    private int LowerRank(int a, int b) => Math.Min(_rank[a], _rank[b]);

    private static bool Touching(Span<double> x, int i, int j, Span<double> radii, double margin)
    {
        var dx = x[3 * i] - x[3 * j];
        var dy = x[(3 * i) + 1] - x[(3 * j) + 1];
        var dz = x[(3 * i) + 2] - x[(3 * j) + 2];
        var ri = radii.Length == 0 ? 0.0 : radii[i];
        var rj = radii.Length == 0 ? 0.0 : radii[j];
        var reach = (1.0 + margin) * (ri + rj);
        return (dx * dx) + (dy * dy) + (dz * dz) <= reach * reach;
    }
}
