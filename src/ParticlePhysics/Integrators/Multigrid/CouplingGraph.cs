using System;
using System.Collections.Generic;

namespace ParticlePhysics.Integrators.Multigrid;

/// <summary>
/// The couplings of one level as an undirected graph with weighted edges (rows sorted by column), and the
/// aggregation that makes the next level from it: pairwise matchings by weight (<see cref="PairTwice"/>), a function
/// of the topology alone, so that a restored run rebuilds the same hierarchy.
/// </summary>
internal sealed class CouplingGraph
{
    public CouplingGraph(int count, int[] rowStart, int[] column, int[] weight)
    {
        Count = count;
        RowStart = rowStart;
        Column = column;
        Weight = weight;
    }

    public int Count { get; }

    public int[] RowStart { get; }

    public int[] Column { get; }

    public int[] Weight { get; }

    public int EdgeCount => Column.Length;

    /// <summary>The graph of the pairs (both directions, self-pairs dropped), a repeated pair weighing its multiplicity.</summary>
    public static CouplingGraph FromPairs(int count, int[] first, int[] second, int pairs)
    {
        var rows = new List<int>[count];
        for (var e = 0; e < pairs; e++)
        {
            if (first[e] != second[e])
            {
                (rows[first[e]] ??= new List<int>()).Add(second[e]);
                (rows[second[e]] ??= new List<int>()).Add(first[e]);
            }
        }

        return FromRows(count, rows, null);
    }

    /// <summary>The graph of the groups of <paramref name="map"/>: weights summed, edges inside a group dropped.</summary>
    public CouplingGraph Contract(int[] map, int groups)
    {
        var rows = new List<int>[groups];
        var weights = new List<int>[groups];
        for (var i = 0; i < Count; i++)
        {
            for (var k = RowStart[i]; k < RowStart[i + 1]; k++)
            {
                int a = map[i], b = map[Column[k]];
                if (a != b)
                {
                    (rows[a] ??= new List<int>()).Add(b);
                    (weights[a] ??= new List<int>()).Add(Weight[k]);
                }
            }
        }

        return FromRows(groups, rows, weights);
    }

    /// <summary>Two pairwise matchings in a row: aggregates of up to four.</summary>
    public static int[] PairTwice(CouplingGraph graph, out int count)
    {
        var first = graph.Match(out var firstCount);
        var second = graph.Contract(first, firstCount).Match(out count);
        var map = new int[graph.Count];
        for (var i = 0; i < map.Length; i++)
        {
            map[i] = second[first[i]];
        }

        return map;
    }

    /// <summary>The members of each group in increasing order (compressed rows).</summary>
    public static (int[] Start, int[] Members) Members(int[] map, int groups)
    {
        var start = new int[groups + 1];
        foreach (var g in map)
        {
            start[g + 1]++;
        }

        for (var g = 0; g < groups; g++)
        {
            start[g + 1] += start[g];
        }

        var members = new int[map.Length];
        var fill = (int[])start.Clone();
        for (var i = 0; i < map.Length; i++)
        {
            members[fill[map[i]]++] = i;
        }

        return (start, members);
    }

    /// <summary>
    /// Greedy matching in increasing node order: each unmatched node pairs with its unmatched neighbour of largest
    /// weight (the lowest-numbered on a tie), or stays alone. Returns each node's group.
    /// </summary>
    private int[] Match(out int groups)
    {
        var group = new int[Count];
        Array.Fill(group, -1);
        groups = 0;
        for (var i = 0; i < Count; i++)
        {
            if (group[i] >= 0)
            {
                continue;
            }

            int best = -1, bestWeight = 0;
            for (var k = RowStart[i]; k < RowStart[i + 1]; k++)
            {
                var j = Column[k];
                if (group[j] < 0 && Weight[k] > bestWeight)
                {
                    best = j;
                    bestWeight = Weight[k];
                }
            }

            group[i] = groups;
            if (best >= 0)
            {
                group[best] = groups;
            }

            groups++;
        }

        return group;
    }

    private static CouplingGraph FromRows(int count, List<int>[] rows, List<int>[]? weights)
    {
        var rowStart = new int[count + 1];
        var columns = new List<int>();
        var weightList = new List<int>();
        var merged = new SortedDictionary<int, int>();
        for (var i = 0; i < count; i++)
        {
            merged.Clear();
            if (rows[i] is { } row)
            {
                for (var k = 0; k < row.Count; k++)
                {
                    merged.TryGetValue(row[k], out var w);
                    merged[row[k]] = w + (weights is null ? 1 : weights[i][k]);
                }
            }

            foreach (var pair in merged)
            {
                columns.Add(pair.Key);
                weightList.Add(pair.Value);
            }

            rowStart[i + 1] = columns.Count;
        }

        return new CouplingGraph(count, rowStart, columns.ToArray(), weightList.ToArray());
    }
}
