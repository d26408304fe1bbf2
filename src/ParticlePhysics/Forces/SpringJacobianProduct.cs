using System;
using System.Runtime.CompilerServices;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Forces;

/// <summary>
/// The spring network's Jacobian product y += J w, on one thread or several, with the same bits: the particles are
/// split into parts (contiguous index ranges; one part on one thread), and each part runs the product's loop over the
/// springs that touch it, in increasing spring order, adding only into the ends it owns. A spring with both ends in
/// one part is computed once; a spring that joins two parts is computed by both (the same operations on the same
/// inputs, so the same 3-vector), each adding into its own end.
/// </summary>
/// <remarks>
/// <para>
/// Spring s with ends a and b and linearisation s I + t u u^T adds y_s = (s I + t u u^T)(w_a - w_b) at a and subtracts
/// it at b. Every particle receives its springs' terms in increasing spring order whatever the parts, as in one loop
/// over all springs, so the sums, hence the bits, depend neither on the number of parts nor on which thread runs
/// which. A part's springs are kept as segments, ranges of consecutive springs whose ends it owns alike (both, the
/// first only, the second only), so that the loop over a segment is the plain loop over a range of springs; with one
/// part there is one segment, all the springs.
/// </para>
/// <para>
/// The loop runs over runs of consecutive springs that share their first end (a cloth adds its springs particle by
/// particle): that end's w is loaded once and its sum kept in registers until the run ends, instead of each addition
/// waiting for the store of the one before. The same additions in the same order (no spring of a run has the run's
/// particle as its second end, and a run cut at a segment's end stores and reloads its sum exactly). On a runner it
/// writes no per-spring slots to gather afterwards, so a product is one pass and one hand-off. The segments are built
/// when the springs, the particles or the number of parts change, never per product.
/// </para>
/// </remarks>
internal sealed unsafe class SpringJacobianProduct : IParallelWork
{
    // What a segment's part owns of its springs' ends.
    private const int OwnsFirst = 1;
    private const int OwnsSecond = 2;
    private const int OwnsBoth = OwnsFirst | OwnsSecond;

    // Segment g is springs [_segments[3 g], _segments[3 g + 1]) with ownership _segments[3 g + 2]; part p's segments
    // are [_partStart[p], _partStart[p + 1]).
    private int[] _partStart = Array.Empty<int>();
    private int[] _segments = Array.Empty<int>();
    private int _springs = -1;
    private int _topology = -1;
    private int _particles = -1;
    private int _parts = -1;

    private double* _w;
    private double* _y;
    private double* _linear;
    private int* _first;
    private int* _second;

    /// <summary>The parts of the last product (0 before the first).</summary>
    public int Parts => Math.Max(0, _parts);

    /// <summary>The springs computed per product over all parts: the spring count plus those joining two parts.</summary>
    public long SpringsComputed
    {
        get
        {
            long total = 0;
            for (var g = 0; g < _segments.Length; g += 3)
            {
                total += _segments[g + 1] - _segments[g];
            }

            return total;
        }
    }

    /// <summary>
    /// y += J w for the first <paramref name="count"/> springs of <paramref name="pairs"/>, linearised in
    /// <paramref name="linear"/> (5 values each: u, s, t), over <paramref name="parts"/> parts: on
    /// <paramref name="runner"/>, or in order on the calling thread without one. The caller checked that the ends are
    /// below <paramref name="particles"/> and that w and y hold 3 values per particle; <paramref name="topology"/> is
    /// its topology version, which changes whenever its springs' ends may have (the segments are rebuilt then).
    /// </summary>
    public void Product(
        double* w, double* y, double* linear, ForceElements pairs, int count, int topology, int particles, int parts, IParallelRunner? runner)
    {
        Update(pairs, count, topology, particles, parts);
        fixed (int* first = pairs.First, second = pairs.Second)
        {
            _w = w;
            _y = y;
            _linear = linear;
            _first = first;
            _second = second;
            try
            {
                Chunk.RunAll(runner, this, _parts);
            }
            finally
            {
                _w = _y = _linear = null;
                _first = _second = null;
            }
        }
    }

    /// <summary>Rebuilds the parts' segments when the springs, their topology, the particles or the parts changed.</summary>
    private void Update(ForceElements pairs, int count, int topology, int particles, int parts)
    {
        if (count == _springs && topology == _topology && particles == _particles && parts == _parts)
        {
            return;
        }

        // Part p owns particles Chunk.Range(p, parts, particles).
        var partOf = new int[particles];
        for (var p = 0; p < parts; p++)
        {
            var (begin, end) = Chunk.Range(p, parts, particles);
            for (var i = begin; i < end; i++)
            {
                partOf[i] = p;
            }
        }

        var lists = new System.Collections.Generic.List<int>[parts];
        for (var p = 0; p < parts; p++)
        {
            lists[p] = new System.Collections.Generic.List<int>();
        }

        for (var s = 0; s < count; s++)
        {
            int pa = partOf[pairs.First[s]], pb = partOf[pairs.Second[s]];
            if (pa == pb)
            {
                Append(lists[pa], s, OwnsBoth);
            }
            else
            {
                Append(lists[pa], s, OwnsFirst);
                Append(lists[pb], s, OwnsSecond);
            }
        }

        var start = new int[parts + 1];
        for (var p = 0; p < parts; p++)
        {
            start[p + 1] = start[p] + (lists[p].Count / 3);
        }

        var segments = new int[3 * start[parts]];
        for (var p = 0; p < parts; p++)
        {
            lists[p].CopyTo(segments, 3 * start[p]);
        }

        _partStart = start;
        _segments = segments;
        _springs = count;
        _topology = topology;
        _particles = particles;
        _parts = parts;
    }

    /// <summary>Adds spring s to a part's segments: it extends the last one when it follows it with the same ownership.</summary>
    private static void Append(System.Collections.Generic.List<int> segments, int s, int owns)
    {
        var last = segments.Count - 3;
        if (last >= 0 && segments[last + 1] == s && segments[last + 2] == owns)
        {
            segments[last + 1] = s + 1;
            return;
        }

        segments.Add(s);
        segments.Add(s + 1);
        segments.Add(owns);
    }

    /// <summary>Part <paramref name="chunk"/>: the product's loop over each of its segments, into the ends it owns.</summary>
    public void Execute(int chunk, int chunkCount)
    {
        for (var g = _partStart[chunk]; g < _partStart[chunk + 1]; g++)
        {
            int begin = _segments[3 * g], end = _segments[(3 * g) + 1], owns = _segments[(3 * g) + 2];
            switch (owns)
            {
                case OwnsBoth:
                    Runs(begin, end, second: true);
                    break;
                case OwnsFirst:
                    Runs(begin, end, second: false);
                    break;
                default:
                    SecondEnds(begin, end);
                    break;
            }
        }
    }

    /// <summary>Springs [begin, end) run by run: the first end's sum in registers, the second end's term subtracted when <paramref name="second"/>.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private void Runs(int begin, int end, bool second)
    {
        double* w = _w, y = _y, linear = _linear;
        int* firstEnds = _first, secondEnds = _second;
        var s = begin;
        while (s < end)
        {
            long a = 3L * firstEnds[s];
            double* ya = y + a;
            double wax = w[a], way = w[a + 1], waz = w[a + 2];
            double sx = ya[0], sy = ya[1], sz = ya[2];
            do
            {
                long b = 3L * secondEnds[s];
                double* wb = w + b, q = linear + (5L * s);
                double dx = wax - wb[0], dy = way - wb[1], dz = waz - wb[2];
                double ux = q[0], uy = q[1], uz = q[2], iso = q[3];
                var axial = q[4] * ((ux * dx) + (uy * dy) + (uz * dz));
                double yx = (iso * dx) + (axial * ux), yy = (iso * dy) + (axial * uy), yz = (iso * dz) + (axial * uz);
                sx += yx;
                sy += yy;
                sz += yz;
                if (second)
                {
                    double* yb = y + b;
                    yb[0] -= yx;
                    yb[1] -= yy;
                    yb[2] -= yz;
                }

                s++;
            }
            while (s < end && 3L * firstEnds[s] == a);

            ya[0] = sx;
            ya[1] = sy;
            ya[2] = sz;
        }
    }

    /// <summary>Springs [begin, end) whose second ends alone are the part's: each one's term subtracted there.</summary>
    private void SecondEnds(int begin, int end)
    {
        double* w = _w, y = _y, linear = _linear;
        for (var s = begin; s < end; s++)
        {
            long a = 3L * _first[s], b = 3L * _second[s];
            double* wa = w + a, wb = w + b, yb = y + b, q = linear + (5L * s);
            double dx = wa[0] - wb[0], dy = wa[1] - wb[1], dz = wa[2] - wb[2];
            double ux = q[0], uy = q[1], uz = q[2], iso = q[3];
            var axial = q[4] * ((ux * dx) + (uy * dy) + (uz * dz));
            yb[0] -= (iso * dx) + (axial * ux);
            yb[1] -= (iso * dy) + (axial * uy);
            yb[2] -= (iso * dz) + (axial * uz);
        }
    }
}
