using System;
using System.Collections.Generic;

namespace ParticlePhysics.Contacts;

/// <summary>
/// The broad phase between particles and obstacles: which obstacles a particle's box may reach within an interval,
/// from each obstacle's box swept over the interval (<see cref="Obstacle.TryGetBounds"/> at the interval's start and
/// end; an obstacle without bounds, a plane, is a candidate for every particle). Any number of obstacles.
/// </summary>
/// <remarks>
/// <para>
/// Rebuilt at the start of every step or substep, since obstacles move: up to <see cref="TreeThreshold"/> bounded
/// obstacles are scanned (a test of one box each beats a tree's descent), above that a <see cref="BoxTree"/> over their
/// boxes answers each query in O(log K) for K obstacles. Either way a query gives the obstacles in increasing index
/// order, the order the contact stages visit them in, so the candidates change which obstacles are tested, never the
/// order of what is done: a stage that tests only the candidates gives the bits of one that tests every obstacle,
/// because an obstacle whose box the particle's box misses cannot touch it.
/// </para>
/// <para>
/// Conservative by a margin: the boxes are grown by 1e-9 m and 1e-12 of their coordinates' magnitude, far above the
/// rounding of a distance (a few 1e-16 of the coordinates) and the contact search's tolerance (1e-10 m and 1e-15 of
/// the coordinates), so no contact the stages would find is left out by the boxes' rounding.
/// </para>
/// </remarks>
internal sealed class ObstacleBroadPhase
{
    /// <summary>Above this many bounded obstacles the queries descend a tree.</summary>
    public const int TreeThreshold = 8;

    private readonly BoxTree _tree = new();
    private double[] _min = Array.Empty<double>();
    private double[] _max = Array.Empty<double>();
    private int[] _bounded = Array.Empty<int>();
    private bool[] _isBounded = Array.Empty<bool>();
    private CollisionFilter[] _filters = Array.Empty<CollisionFilter>();
    private int _count;
    private int _boundedCount;

    /// <summary>For tests: every obstacle is a candidate (what the stages did before the broad phase), to compare bits.</summary>
    public bool Disabled { get; set; }

    /// <summary>The obstacles of the last <see cref="Update"/>.</summary>
    public int Count => _count;

    /// <summary>The obstacles' boxes swept over the times [<paramref name="from"/>, <paramref name="to"/>].</summary>
    public void Update(IReadOnlyList<Obstacle> obstacles, double from, double to)
    {
        var count = obstacles.Count;
        if (_isBounded.Length < count)
        {
            var capacity = Math.Max(count, 2 * _isBounded.Length);
            _min = new double[3 * capacity];
            _max = new double[3 * capacity];
            _bounded = new int[capacity];
            _isBounded = new bool[capacity];
            _filters = new CollisionFilter[capacity];
        }

        _count = count;
        _boundedCount = 0;
        for (var k = 0; k < count; k++)
        {
            var obstacle = obstacles[k];
            _filters[k] = obstacle.Filter;
            _isBounded[k] = false;
            if (!obstacle.TryGetBounds(out var min, out var max))
            {
                continue;
            }

            var a = obstacle.OffsetAt(from);
            var b = obstacle.OffsetAt(to);
            var lo = min + new Vector3d(Math.Min(a.X, b.X), Math.Min(a.Y, b.Y), Math.Min(a.Z, b.Z));
            var hi = max + new Vector3d(Math.Max(a.X, b.X), Math.Max(a.Y, b.Y), Math.Max(a.Z, b.Z));
            var magnitude = Math.Max(MaxAbs(lo), MaxAbs(hi)) + Math.Max(MaxAbs(min), MaxAbs(max));
            var grow = 1e-9 + (1e-12 * magnitude);
            if (!(grow < double.PositiveInfinity) || !(lo.X <= hi.X && lo.Y <= hi.Y && lo.Z <= hi.Z))
            {
                continue; // bounds that are not finite bound nothing: tested against every particle
            }

            var o = 3 * _boundedCount;
            (_min[o], _min[o + 1], _min[o + 2]) = (lo.X - grow, lo.Y - grow, lo.Z - grow);
            (_max[o], _max[o + 1], _max[o + 2]) = (hi.X + grow, hi.Y + grow, hi.Z + grow);
            _bounded[_boundedCount++] = k;
            _isBounded[k] = true;
        }

        if (_boundedCount > TreeThreshold)
        {
            _tree.Build(_min, _max, _boundedCount);
        }
    }

    /// <summary>
    /// Writes into <paramref name="candidates"/> (grown as needed), in increasing order, the obstacles after
    /// <paramref name="after"/> whose swept box meets [lo, hi] and whose filter accepts <paramref name="filter"/>;
    /// returns how many.
    /// </summary>
    public int Collect(Vector3d lo, Vector3d hi, CollisionFilter filter, int after, ref int[] candidates)
    {
        if (candidates.Length < _count)
        {
            candidates = new int[Math.Max(_count, 2 * candidates.Length)];
        }

        var grow = 1e-9 + (1e-12 * Math.Max(MaxAbs(lo), MaxAbs(hi)));
        double x0 = lo.X - grow, y0 = lo.Y - grow, z0 = lo.Z - grow;
        double x1 = hi.X + grow, y1 = hi.Y + grow, z1 = hi.Z + grow;
        var found = 0;
        if (Disabled)
        {
            for (var k = after + 1; k < _count; k++)
            {
                if (_filters[k].Accepts(filter))
                {
                    candidates[found++] = k;
                }
            }

            return found;
        }

        if (_boundedCount <= TreeThreshold)
        {
            var b = 0;
            for (var k = after + 1; k < _count; k++)
            {
                while (b < _boundedCount && _bounded[b] < k)
                {
                    b++;
                }

                if (!_filters[k].Accepts(filter))
                {
                    continue;
                }

                if (!_isBounded[k] || Overlaps(b, x0, y0, z0, x1, y1, z1))
                {
                    candidates[found++] = k;
                }
            }

            return found;
        }

        for (var k = after + 1; k < _count; k++)
        {
            if (!_isBounded[k] && _filters[k].Accepts(filter))
            {
                candidates[found++] = k;
            }
        }

        Span<int> stack = stackalloc int[BoxTree.MaxDepth];
        var top = 0;
        stack[top++] = 0;
        while (top > 0)
        {
            var node = stack[--top];
            if (!_tree.Overlaps(node, x0, y0, z0, x1, y1, z1))
            {
                continue;
            }

            var first = _tree.NodeFirst[node];
            var leaf = _tree.NodeCount[node];
            if (leaf == 0)
            {
                stack[top++] = first + 1;
                stack[top++] = first;
                continue;
            }

            for (var e = first; e < first + leaf; e++)
            {
                var b = _tree.Items[e];
                var k = _bounded[b];
                if (k > after && _filters[k].Accepts(filter) && Overlaps(b, x0, y0, z0, x1, y1, z1))
                {
                    candidates[found++] = k;
                }
            }
        }

        Array.Sort(candidates, 0, found);
        return found;
    }

    private bool Overlaps(int b, double x0, double y0, double z0, double x1, double y1, double z1)
    {
        var o = 3 * b;
        return _min[o] <= x1 && x0 <= _max[o] && _min[o + 1] <= y1 && y0 <= _max[o + 1] && _min[o + 2] <= z1 && z0 <= _max[o + 2];
    }

    private static double MaxAbs(Vector3d v) => Math.Max(Math.Abs(v.X), Math.Max(Math.Abs(v.Y), Math.Abs(v.Z)));
}
