using System;

namespace ParticlePhysics.Contacts;

/// <summary>
/// A bounding volume hierarchy over axis-aligned boxes in flat arrays: the triangles of a mesh (built once), the
/// obstacles of a contact set (rebuilt each step). Node n has the box [<see cref="NodeMin"/>, <see cref="NodeMax"/>]
/// (3 values each); a leaf (<see cref="NodeCount"/> &gt; 0) holds the items <see cref="Items"/>[first, first + count),
/// an inner node (count 0) has its two children at first and first + 1. Node 0 is the root.
/// </summary>
/// <remarks>
/// <para>
/// Built top-down: each node splits its items at the median of their box centres along the longest axis of the
/// centres' bounds (a selection in place, ties by item index, so the tree is a function of the boxes alone), until a
/// leaf holds at most <see cref="LeafSize"/>. Halving the count bounds the depth by log2(N / LeafSize) + 2, at most
/// 32 for any array .NET can hold, so every traversal fits a fixed stack of <see cref="MaxDepth"/> entries (a
/// traversal pushes at most one node per level besides the one it visits) and allocates nothing. A median split
/// rather than the surface-area heuristic: the build is O(N log N) with no tuning, and queries on meshes scanned or
/// generated in any order cost within a small factor of the best tree.
/// </para>
/// <para>The arrays grow to the largest set built and are kept, so rebuilding for as many boxes allocates nothing.</para>
/// </remarks>
internal sealed class BoxTree
{
    /// <summary>The most items in a leaf.</summary>
    public const int LeafSize = 4;

    /// <summary>A bound on the depth of any tree, the size of a traversal's stack.</summary>
    public const int MaxDepth = 64;

    private double[] _centre = Array.Empty<double>();

    /// <summary>The number of nodes (0 for an empty tree).</summary>
    public int Nodes { get; private set; }

    /// <summary>The nodes' lower corners, 3 per node.</summary>
    public double[] NodeMin { get; private set; } = Array.Empty<double>();

    /// <summary>The nodes' upper corners, 3 per node.</summary>
    public double[] NodeMax { get; private set; } = Array.Empty<double>();

    /// <summary>A leaf's first item, or an inner node's first child.</summary>
    public int[] NodeFirst { get; private set; } = Array.Empty<int>();

    /// <summary>A leaf's number of items; 0 for an inner node.</summary>
    public int[] NodeCount { get; private set; } = Array.Empty<int>();

    /// <summary>The items (indices of the boxes built from), in the order of the leaves.</summary>
    public int[] Items { get; private set; } = Array.Empty<int>();

    /// <summary>Builds the tree over <paramref name="count"/> boxes, box i being [min[3i..3i+2], max[3i..3i+2]].</summary>
    public void Build(Span<double> min, Span<double> max, int count)
    {
        if (Items.Length < count)
        {
            Items = new int[count];
            _centre = new double[3 * count];
            // Halving until at most 4 leaves leaves of 2.5 items at worst (N = 5 2^k): at most 0.4 N + 1 leaves, so
            // fewer than N + 1 nodes.
            var nodes = count + 1;
            NodeMin = new double[3 * nodes];
            NodeMax = new double[3 * nodes];
            NodeFirst = new int[nodes];
            NodeCount = new int[nodes];
        }

        for (var i = 0; i < count; i++)
        {
            Items[i] = i;
            for (var c = 0; c < 3; c++)
            {
                _centre[(3 * i) + c] = 0.5 * (min[(3 * i) + c] + max[(3 * i) + c]);
            }
        }

        Nodes = 0;
        if (count == 0)
        {
            return;
        }

        Nodes = 1;
        Split(0, 0, count, min, max);
    }

    /// <summary>Whether node <paramref name="node"/>'s box and [min, max] overlap (touching counts).</summary>
    public bool Overlaps(int node, double minX, double minY, double minZ, double maxX, double maxY, double maxZ)
    {
        var o = 3 * node;
        return NodeMin[o] <= maxX && minX <= NodeMax[o]
            && NodeMin[o + 1] <= maxY && minY <= NodeMax[o + 1]
            && NodeMin[o + 2] <= maxZ && minZ <= NodeMax[o + 2];
    }

    /// <summary>The distance from (x, y, z) to node <paramref name="node"/>'s box (0 inside).</summary>
    public double DistanceTo(int node, double x, double y, double z)
    {
        var o = 3 * node;
        var dx = Math.Max(Math.Max(NodeMin[o] - x, x - NodeMax[o]), 0.0);
        var dy = Math.Max(Math.Max(NodeMin[o + 1] - y, y - NodeMax[o + 1]), 0.0);
        var dz = Math.Max(Math.Max(NodeMin[o + 2] - z, z - NodeMax[o + 2]), 0.0);
        return Math.Sqrt((dx * dx) + (dy * dy) + (dz * dz));
    }

    /// <summary>
    /// The parameter interval [near, far] within [0, <paramref name="limit"/>] over which the ray o + t d is inside node
    /// <paramref name="node"/>'s box grown by <paramref name="grow"/> (the slab test; <paramref name="inverse"/> holds
    /// 1 / d per axis, infinite for a zero component); false when it misses.
    /// </summary>
    public bool RayEnters(int node, Vector3d o, Vector3d inverse, double grow, double limit, out double near)
    {
        var b = 3 * node;
        near = 0.0;
        var far = limit;
        for (var c = 0; c < 3; c++)
        {
            var origin = c == 0 ? o.X : c == 1 ? o.Y : o.Z;
            var slope = c == 0 ? inverse.X : c == 1 ? inverse.Y : inverse.Z;
            var lo = NodeMin[b + c] - grow;
            var hi = NodeMax[b + c] + grow;
            if (double.IsInfinity(slope))
            {
                if (origin < lo || origin > hi)
                {
                    return false;
                }

                continue;
            }

            var t0 = (lo - origin) * slope;
            var t1 = (hi - origin) * slope;
            if (t0 > t1)
            {
                (t0, t1) = (t1, t0);
            }

            near = Math.Max(near, t0);
            far = Math.Min(far, t1);
            if (near > far)
            {
                return false;
            }
        }

        return true;
    }

    /// <summary>Node <paramref name="node"/> over Items[start, end): its box, then a leaf or a split at the median.</summary>
    private void Split(int node, int start, int end, Span<double> min, Span<double> max)
    {
        double lx = double.PositiveInfinity, ly = double.PositiveInfinity, lz = double.PositiveInfinity;
        double hx = double.NegativeInfinity, hy = double.NegativeInfinity, hz = double.NegativeInfinity;
        double cx0 = double.PositiveInfinity, cy0 = double.PositiveInfinity, cz0 = double.PositiveInfinity;
        double cx1 = double.NegativeInfinity, cy1 = double.NegativeInfinity, cz1 = double.NegativeInfinity;
        for (var k = start; k < end; k++)
        {
            var o = 3 * Items[k];
            lx = Math.Min(lx, min[o]);
            ly = Math.Min(ly, min[o + 1]);
            lz = Math.Min(lz, min[o + 2]);
            hx = Math.Max(hx, max[o]);
            hy = Math.Max(hy, max[o + 1]);
            hz = Math.Max(hz, max[o + 2]);
            cx0 = Math.Min(cx0, _centre[o]);
            cy0 = Math.Min(cy0, _centre[o + 1]);
            cz0 = Math.Min(cz0, _centre[o + 2]);
            cx1 = Math.Max(cx1, _centre[o]);
            cy1 = Math.Max(cy1, _centre[o + 1]);
            cz1 = Math.Max(cz1, _centre[o + 2]);
        }

        var b = 3 * node;
        (NodeMin[b], NodeMin[b + 1], NodeMin[b + 2]) = (lx, ly, lz);
        (NodeMax[b], NodeMax[b + 1], NodeMax[b + 2]) = (hx, hy, hz);
        if (end - start <= LeafSize)
        {
            NodeFirst[node] = start;
            NodeCount[node] = end - start;
            return;
        }

        var ex = cx1 - cx0;
        var ey = cy1 - cy0;
        var ez = cz1 - cz0;
        var axis = ex >= ey && ex >= ez ? 0 : ey >= ez ? 1 : 2;
        var middle = start + ((end - start) / 2);
        Select(start, end - 1, middle, axis);
        var left = Nodes;
        Nodes += 2;
        NodeFirst[node] = left;
        NodeCount[node] = 0;
        Split(left, start, middle, min, max);
        Split(left + 1, middle, end, min, max);
    }

    /// <summary>Places the item of rank <paramref name="k"/> (by centre along <paramref name="axis"/>, then index) at k, smaller ones before it (Hoare's selection).</summary>
    private void Select(int lo, int hi, int k, int axis)
    {
        while (hi > lo)
        {
            // The median of the first, middle and last as the pivot: sorted input (a scanned grid) stays O(N).
            var mid = lo + ((hi - lo) / 2);
            if (Less(Items[mid], Items[lo], axis))
            {
                Swap(lo, mid);
            }

            if (Less(Items[hi], Items[lo], axis))
            {
                Swap(lo, hi);
            }

            if (Less(Items[hi], Items[mid], axis))
            {
                Swap(mid, hi);
            }

            var pivot = Items[mid];
            var i = lo;
            var j = hi;
            while (i <= j)
            {
                while (Less(Items[i], pivot, axis))
                {
                    i++;
                }

                while (Less(pivot, Items[j], axis))
                {
                    j--;
                }

                if (i <= j)
                {
                    Swap(i, j);
                    i++;
                    j--;
                }
            }

            if (k <= j)
            {
                hi = j;
            }
            else if (k >= i)
            {
                lo = i;
            }
            else
            {
                return;
            }
        }
    }

    private bool Less(int a, int b, int axis)
    {
        var ca = _centre[(3 * a) + axis];
        var cb = _centre[(3 * b) + axis];
        return ca < cb || (ca == cb && a < b);
    }

    private void Swap(int a, int b) => (Items[a], Items[b]) = (Items[b], Items[a]);
}
