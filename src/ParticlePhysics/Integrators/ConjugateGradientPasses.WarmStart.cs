using System;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Integrators;

/// <summary>
/// The warm start: dv from the last steps' dv (their extrapolation, or the combination that the Galerkin conditions
/// choose), and the sums u_a . q_c and u_a . b that choose it.
/// </summary>
internal sealed unsafe partial class ConjugateGradientPasses
{
    private readonly WarmStartPass _warmStart = new();
    private readonly WarmStartGramPass _warmStartGram = new();

    /// <summary>
    /// dv = c_0 u_0 + c_1 u_1 + ... (the first <paramref name="count"/> of <paramref name="vectors"/> and
    /// <paramref name="coefficients"/>, added in that order) on the free particles, 0 on pinned ones: the warm start
    /// from the last steps' dv (c = (2, -1) on the last two is their linear extrapolation).
    /// </summary>
    public void WarmStart(double[][] vectors, double[] coefficients, int count)
    {
        CheckStartVectors(vectors, count, nameof(vectors));
        if (coefficients.Length < count)
        {
            throw new ArgumentException($"The warm start needs {count} coefficients; got {coefficients.Length}.", nameof(coefficients));
        }

        // At most four (WarmStartHistory.Depth): pinned one by one, an absent one as the first.
        fixed (double* u0 = Pick(vectors, 0, count), u1 = Pick(vectors, 1, count), u2 = Pick(vectors, 2, count), u3 = Pick(vectors, 3, count))
        fixed (double* inverseMasses = _inverseMasses, dv = Dv)
        {
            _warmStart.Set(u0, u1, u2, u3, coefficients, count, inverseMasses, dv, _particles);
            Run(_warmStart);
        }
    }

    /// <summary>
    /// The sums that choose the warm start in the span of the last steps' dv u_0 .. u_{count-1}, from their products
    /// q_a ~ A u_a (each step's b - r at its end), over the free particles: <paramref name="gram"/>[a count + c] =
    /// u_a . q_c and <paramref name="projections"/>[a] = u_a . b, each summed in chunk order. Needs b.
    /// </summary>
    public void WarmStartGram(double[][] vectors, double[][] products, int count, double[] gram, double[] projections)
    {
        CheckStartVectors(vectors, count, nameof(vectors));
        CheckStartVectors(products, count, nameof(products));
        if (gram.Length < count * count || projections.Length < count)
        {
            throw new ArgumentException($"The warm start's sums need {count * count} and {count} values.", nameof(gram));
        }

        fixed (double* u0 = Pick(vectors, 0, count), u1 = Pick(vectors, 1, count), u2 = Pick(vectors, 2, count), u3 = Pick(vectors, 3, count))
        fixed (double* q0 = Pick(products, 0, count), q1 = Pick(products, 1, count), q2 = Pick(products, 2, count), q3 = Pick(products, 3, count))
        fixed (double* b = B, inverseMasses = _inverseMasses)
        {
            _warmStartGram.Set(u0, u1, u2, u3, q0, q1, q2, q3, count, b, inverseMasses, _particles);
            Run(_warmStartGram);
        }

        _warmStartGram.Sums(gram, projections);
    }

    /// <summary>Vector <paramref name="a"/> of the first <paramref name="count"/>, or the first when a is past them (a pass reads only count).</summary>
    private static double[] Pick(double[][] from, int a, int count) => from[a < count ? a : 0];

    /// <summary>Checks that there are 1 to <see cref="WarmStartHistory.Depth"/> vectors of 3 values per particle.</summary>
    private void CheckStartVectors(double[][] vectors, int count, string name)
    {
        if (count < 1 || count > WarmStartHistory.Depth || vectors.Length < count)
        {
            throw new ArgumentException($"The warm start takes 1 to {WarmStartHistory.Depth} vectors; got {count} of {vectors.Length}.", name);
        }

        for (var a = 0; a < count; a++)
        {
            CheckLength(vectors[a]);
        }
    }

    /// <summary>dv = c_0 u_0 + ... + c_{count-1} u_{count-1} per chunk of particles, 0 on pinned ones.</summary>
    private sealed class WarmStartPass : IParallelWork
    {
        private double* _u0;
        private double* _u1;
        private double* _u2;
        private double* _u3;
        private double _c0;
        private double _c1;
        private double _c2;
        private double _c3;
        private int _count;
        private double* _inverseMasses;
        private double* _dv;
        private int _particles;

        public void Set(
            double* u0, double* u1, double* u2, double* u3, double[] coefficients, int count, double* inverseMasses,
            double* dv, int particles)
        {
            _u0 = u0;
            _u1 = u1;
            _u2 = u2;
            _u3 = u3;
            _c0 = coefficients[0];
            _c1 = count > 1 ? coefficients[1] : 0.0;
            _c2 = count > 2 ? coefficients[2] : 0.0;
            _c3 = count > 3 ? coefficients[3] : 0.0;
            _count = count;
            _inverseMasses = inverseMasses;
            _dv = dv;
            _particles = particles;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _particles);
            OverRange(begin, end);
        }

        /// <summary>Particles [begin, end): one loop per count, so that each coordinate adds exactly its count terms, in that order.</summary>
        private void OverRange(int begin, int end)
        {
            double* u0 = _u0, u1 = _u1, u2 = _u2, u3 = _u3;
            double c0 = _c0, c1 = _c1, c2 = _c2, c3 = _c3;
            var count = _count;
            for (var i = begin; i < end; i++)
            {
                long o = 3 * i;
                var dv = _dv + o;
                if (_inverseMasses[i] == 0.0)
                {
                    dv[0] = dv[1] = dv[2] = 0.0;
                    continue;
                }

                for (var k = o; k < o + 3; k++)
                {
                    _dv[k] = count switch
                    {
                        1 => c0 * u0[k],
                        2 => (c0 * u0[k]) + (c1 * u1[k]),
                        3 => (c0 * u0[k]) + (c1 * u1[k]) + (c2 * u2[k]),
                        _ => (c0 * u0[k]) + (c1 * u1[k]) + (c2 * u2[k]) + (c3 * u3[k]),
                    };
                }
            }
        }
    }

    /// <summary>
    /// The warm start's sums per chunk of particles, u_a . q_c for every a, c &lt; count and u_a . b, each in increasing
    /// coordinate order over the free particles; added in chunk order by <see cref="Sums"/>.
    /// </summary>
    private sealed class WarmStartGramPass : IParallelWork
    {
        // Each sum per chunk: u_a . q_c for a, c < count (row-major), then u_a . b.
        private readonly double[][] _partials = NewPartials((WarmStartHistory.Depth * WarmStartHistory.Depth) + WarmStartHistory.Depth);
        private readonly IntPtr[] _vectors = new IntPtr[WarmStartHistory.Depth];
        private readonly IntPtr[] _products = new IntPtr[WarmStartHistory.Depth];
        private int _count;
        private double* _b;
        private double* _inverseMasses;
        private int _particles;

        public void Set(
            double* u0, double* u1, double* u2, double* u3, double* q0, double* q1, double* q2, double* q3, int count,
            double* b, double* inverseMasses, int particles)
        {
            (_vectors[0], _vectors[1], _vectors[2], _vectors[3]) = ((IntPtr)u0, (IntPtr)u1, (IntPtr)u2, (IntPtr)u3);
            (_products[0], _products[1], _products[2], _products[3]) = ((IntPtr)q0, (IntPtr)q1, (IntPtr)q2, (IntPtr)q3);
            _count = count;
            _b = b;
            _inverseMasses = inverseMasses;
            _particles = particles;
        }

        /// <summary>The chunks' sums added in chunk order: the u_a . q_c into <paramref name="gram"/>, the u_a . b into <paramref name="projections"/>.</summary>
        public void Sums(double[] gram, double[] projections)
        {
            var count = _count;
            for (var j = 0; j < (count * count) + count; j++)
            {
                var sum = Chunk.Sum(_partials[j]);
                if (j < count * count)
                {
                    gram[j] = sum;
                }
                else
                {
                    projections[j - (count * count)] = sum;
                }
            }
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _particles);
            OverRange(chunk, begin, end);
        }

        /// <summary>
        /// Rows of the warm start's sums for one chunk, u_a . q_0 .. q_{count-1} and u_a . b, in one sweep of the chunk per
        /// two rows: ten sums at a time keep their chains in registers (all of them at once would not), and the chunk's
        /// vectors stay in the cache between the sweeps. Each sum in increasing coordinate order.
        /// </summary>
        private void OverRange(int chunk, int begin, int end)
        {
            var count = _count;
            var sums = stackalloc double[10];
            for (var a = 0; a < count; a += 2)
            {
                var rows = Math.Min(2, count - a);
                GramRows(a, rows, begin, end, sums);
                for (var row = 0; row < rows; row++)
                {
                    for (var c = 0; c < count; c++)
                    {
                        _partials[((a + row) * count) + c][chunk] = sums[(5 * row) + c];
                    }

                    _partials[(count * count) + a + row][chunk] = sums[(5 * row) + 4];
                }
            }
        }

        /// <summary>
        /// Rows a and a + 1 (or row a alone when <paramref name="rows"/> is 1) of the warm start's sums over particles
        /// [<paramref name="begin"/>, <paramref name="end"/>): u_a . q_c for every c and u_a . b, each in increasing
        /// coordinate order, into <paramref name="sums"/> (five per row: the four products, those at c &gt;= count of no use
        /// and read from q_0 again, then b). Two rows at a time so that ten sums run side by side: each sum is a chain of
        /// additions, and two rows' chains keep the processor busy where one row's left it waiting (the same sums in the
        /// same order, so the same bits).
        /// </summary>
        private void GramRows(int a, int rows, int begin, int end, double* sums)
        {
            var count = _count;
            var u = (double*)_vectors[a];
            var v = rows > 1 ? (double*)_vectors[a + 1] : u;
            var q0 = (double*)_products[0];
            var q1 = count > 1 ? (double*)_products[1] : q0;
            var q2 = count > 2 ? (double*)_products[2] : q0;
            var q3 = count > 3 ? (double*)_products[3] : q0;
            double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0, sb = 0.0;
            double t0 = 0.0, t1 = 0.0, t2 = 0.0, t3 = 0.0, tb = 0.0;
            for (var i = begin; i < end; i++)
            {
                if (_inverseMasses[i] == 0.0)
                {
                    continue;
                }

                for (long k = 3 * i; k < (3 * i) + 3; k++)
                {
                    double uk = u[k], vk = v[k], q0k = q0[k], q1k = q1[k], q2k = q2[k], q3k = q3[k], bk = _b[k];
                    s0 += uk * q0k;
                    s1 += uk * q1k;
                    s2 += uk * q2k;
                    s3 += uk * q3k;
                    sb += uk * bk;
                    t0 += vk * q0k;
                    t1 += vk * q1k;
                    t2 += vk * q2k;
                    t3 += vk * q3k;
                    tb += vk * bk;
                }
            }

            (sums[0], sums[1], sums[2], sums[3], sums[4]) = (s0, s1, s2, s3, sb);
            (sums[5], sums[6], sums[7], sums[8], sums[9]) = (t0, t1, t2, t3, tb);
        }

        /// <summary><paramref name="count"/> arrays of one partial sum per chunk.</summary>
        private static double[][] NewPartials(int count)
        {
            var partials = new double[count][];
            for (var j = 0; j < count; j++)
            {
                partials[j] = new double[Chunks];
            }

            return partials;
        }
    }
}
