using System;
using System.Runtime.CompilerServices;
using ParticlePhysics.Integrators.Multigrid;
using ParticlePhysics.Numerics;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Integrators;

/// <summary>
/// The vector passes of implicit Euler's conjugate gradients (Chronopoulos and Gear's form, see
/// <see cref="ImplicitEuler"/>), in a fixed number of chunks of particles whose partial sums are added in chunk order:
/// the same bits whether the chunks run on one thread or on a runner's several.
/// </summary>
/// <remarks>
/// The vectors, 3 values per particle: b the right-hand side, dv the solution, r = b - A dv the residual, z = P r the
/// preconditioned residual, p the search direction and s = A p; jw receives the system's J times a vector (without
/// its uniform tail c w when the system has one, which the residual and z . w passes add before they use jw: see
/// <see cref="SetProductTail"/>), and the pass that reads it last leaves it 0 for the next product (no pass of its own
/// clears it). w = A z = M z - J z is
/// never stored: the pass after the product sums z . w from z and jw (and leaves jw), and the update, which needs w
/// once, computes it again from the same two (the same operations, so the same bits as a stored w) and clears jw,
/// which saves writing and re-reading a vector every iteration; the blocks (9 values
/// per particle) are J_ii, and <see cref="InvertBlocks"/> writes D_i^-1 = (M_i - J_ii)^-1 into the inverses, 6 values
/// per particle: the matrix is symmetric, so its upper triangle xx, xy, xz, yy, yz, zz is all of it, and the passes
/// that apply it every iteration read two thirds of the bytes. A pinned particle's components are 0 in every vector
/// but dv's warm start (filtered there too).
/// </remarks>
internal sealed unsafe class ConjugateGradientPasses : IParallelWork
{
    private const int RightHandSidePass = 1;
    private const int WarmStartPass = 2;
    private const int ResidualPass = 3;
    private const int MassMinusJacobianPass = 4;
    private const int UpdatePass = 5;
    private const int JacobiPass = 6;
    private const int InvertBlocksPass = 7;
    private const int EndStatePass = 8;
    private const int WarmStartGramPass = 9;
    private const int SolutionProductPass = 10;


    private readonly double[] _partial = new double[AggregationMultigrid.Chunks];
    private readonly double[] _secondPartial = new double[AggregationMultigrid.Chunks];
    // The sums of WarmStartGram, each per chunk: u_a . q_c for a, c < count (row-major), then u_a . b.
    private readonly double[][] _gramPartials = NewPartials((WarmStartHistory.Depth * WarmStartHistory.Depth) + WarmStartHistory.Depth);
    private bool _hasTail; // whether this step's products leave out a uniform last term c w (SetProductTail), and c
    private double _tail;
    // The vectors of the warm start passes (pinned for the pass's duration) and their count.
    private readonly IntPtr[] _startVectors = new IntPtr[WarmStartHistory.Depth];
    private readonly IntPtr[] _startProducts = new IntPtr[WarmStartHistory.Depth];
    private readonly double[] _startCoefficients = new double[WarmStartHistory.Depth];
    private int _startCount;
    private double[] _masses = Array.Empty<double>();
    private double[] _coordinateMasses = Array.Empty<double>();
    private double[] _inverses = Array.Empty<double>();
    private double[] _inverseMasses = Array.Empty<double>();
    private IParallelRunner? _runner;
    private int _particles;

    // The operation of the pass under way and its arguments (pinned for the pass's duration).
    private int _operation;
    private double* _a;
    private double* _b;
    private double* _c;
    private double* _d;
    private double _scalar;
    private double _secondScalar;
    private double* _pB;
    private double* _pDv;
    private double* _pR;
    private double* _pP;
    private double* _pS;
    private double* _pZ;
    private double* _pJw;
    private double* _pBlocks;
    private double* _pInverses;
    private double* _pMasses;
    private double* _pInverseMasses;

    /// <summary>The right-hand side b.</summary>
    public double[] B { get; private set; } = Array.Empty<double>();

    /// <summary>The solution dv.</summary>
    public double[] Dv { get; private set; } = Array.Empty<double>();

    /// <summary>The residual r = b - A dv.</summary>
    public double[] R { get; private set; } = Array.Empty<double>();

    /// <summary>The search direction p.</summary>
    public double[] P { get; private set; } = Array.Empty<double>();

    /// <summary>s = A p.</summary>
    public double[] S { get; private set; } = Array.Empty<double>();

    /// <summary>The preconditioned residual z.</summary>
    public double[] Z { get; private set; } = Array.Empty<double>();

    /// <summary>
    /// The system's J times a vector, which <see cref="Residual"/>, <see cref="MassMinusJacobian"/> and the update read;
    /// with a product tail (<see cref="SetProductTail"/>), J w without c w until one of the first two adds it.
    /// </summary>
    public double[] JacobianProduct { get; private set; } = Array.Empty<double>();

    /// <summary>The diagonal blocks J_ii (9 values per particle, row-major), as the forces added them.</summary>
    public double[] Blocks { get; private set; } = Array.Empty<double>();

    /// <summary>
    /// D_i^-1 = (M_i - J_ii)^-1 after <see cref="InvertBlocks"/>, 6 values per particle: the upper triangle
    /// xx, xy, xz, yy, yz, zz of the symmetric block (<see cref="Blocks3.MultiplySymmetric"/> applies it).
    /// </summary>
    public double[] Inverses => _inverses;

    /// <summary>This step's masses, a copy the passes own (0 for pinned particles).</summary>
    public double[] Masses => _masses;

    /// <summary><see cref="Masses"/> once per coordinate (3 values per particle), for the passes that run over coordinates with SIMD.</summary>
    public double[] CoordinateMasses => _coordinateMasses;

    /// <summary>This step's inverse masses (0 for pinned particles), a copy the passes own.</summary>
    public double[] InverseMasses => _inverseMasses;

    /// <summary>The number of particles the vectors are bound for.</summary>
    public int Particles => _particles;

    /// <summary>r . z of the last <see cref="Update"/> with block Jacobi (the pass computes z = D^-1 r as it goes).</summary>
    public double LastJacobiProduct { get; private set; }

    public void Bind(
        double[] b, double[] dv, double[] r, double[] p, double[] s, double[] z, double[] jw, double[] blocks,
        Span<double> masses, Span<double> inverseMasses, IParallelRunner? runner)
    {
        // Every pass runs its pointers over 3 values per particle (9 for the blocks, 6 for the inverses the passes own):
        // checked here, where they are bound.
        var n = 3L * masses.Length;
        if (inverseMasses.Length != masses.Length || b.Length < n || dv.Length < n || r.Length < n || p.Length < n
            || s.Length < n || z.Length < n || jw.Length < n || blocks.Length < 3 * n)
        {
            throw new ArgumentException(
                $"The conjugate gradients' vectors need {n} values each and the blocks {3 * n} for {masses.Length} particles.");
        }

        if (_masses.Length != masses.Length)
        {
            _masses = new double[masses.Length];
            _coordinateMasses = new double[3 * masses.Length];
            _inverseMasses = new double[masses.Length];
            _inverses = new double[6 * masses.Length];
        }

        // A pinned particle's mass is 0 in the passes' copy: the update computes w = M z - jw on every particle, and a
        // system may report a pinned particle's mass as infinite (infinity times z = 0 would be NaN there). No pass
        // reads a pinned particle's mass otherwise.
        inverseMasses.CopyTo(_inverseMasses);
        for (var i = 0; i < masses.Length; i++)
        {
            var mass = inverseMasses[i] == 0.0 ? 0.0 : masses[i];
            _masses[i] = mass;
            _coordinateMasses[3 * i] = _coordinateMasses[(3 * i) + 1] = _coordinateMasses[(3 * i) + 2] = mass;
        }

        B = b;
        Dv = dv;
        R = r;
        P = p;
        S = s;
        Z = z;
        JacobianProduct = jw;
        Blocks = blocks;
        _runner = runner;
        _particles = masses.Length;
    }

    private void CheckLength(double[] values)
    {
        if (values.Length < 3L * _particles)
        {
            throw new ArgumentException($"A vector of the conjugate gradients needs {3L * _particles} values; it has {values.Length}.");
        }
    }

    /// <summary>b = h (f + h jw) on the free particles, 0 on pinned ones (jw = K v0), then jw = 0; returns b . b.</summary>
    public double RightHandSide(double[] force, double h)
    {
        CheckLength(force);
        fixed (double* f = force)
        {
            _a = f;
            _scalar = h;
            return Run(RightHandSidePass);
        }
    }

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

        Array.Copy(coefficients, _startCoefficients, count);
        RunOverStartVectors(WarmStartPass, vectors, null, count);
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

        RunOverStartVectors(WarmStartGramPass, vectors, products, count);
        for (var j = 0; j < (count * count) + count; j++)
        {
            var sum = Chunk.Sum(_gramPartials[j]);
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

    /// <summary>Runs <paramref name="operation"/> with the first <paramref name="count"/> vectors (and products) pinned.</summary>
    private void RunOverStartVectors(int operation, double[][] vectors, double[][]? products, int count)
    {
        // At most four of each (WarmStartHistory.Depth): pinned one by one, an absent one as the first.
        double[] Pick(double[][] from, int a) => from[a < count ? a : 0];
        fixed (double* u0 = Pick(vectors, 0), u1 = Pick(vectors, 1), u2 = Pick(vectors, 2), u3 = Pick(vectors, 3))
        fixed (double* q0 = products is null ? null : Pick(products, 0), q1 = products is null ? null : Pick(products, 1))
        fixed (double* q2 = products is null ? null : Pick(products, 2), q3 = products is null ? null : Pick(products, 3))
        {
            (_startVectors[0], _startVectors[1], _startVectors[2], _startVectors[3]) = ((IntPtr)u0, (IntPtr)u1, (IntPtr)u2, (IntPtr)u3);
            (_startProducts[0], _startProducts[1], _startProducts[2], _startProducts[3]) = ((IntPtr)q0, (IntPtr)q1, (IntPtr)q2, (IntPtr)q3);
            _startCount = count;
            try
            {
                _ = Run(operation);
            }
            finally
            {
                Array.Clear(_startVectors, 0, _startVectors.Length); // no address outlives its pinning
                Array.Clear(_startProducts, 0, _startProducts.Length);
            }
        }
    }

    /// <summary>q = b - r on the free particles, 0 on pinned ones: A dv for the solution just found, up to the solve's residual.</summary>
    public void SolutionProduct(double[] product)
    {
        CheckLength(product);
        fixed (double* q = product)
        {
            _a = q;
            _ = Run(SolutionProductPass);
        }
    }

    /// <summary>
    /// The uniform last term of this step's Jacobian products, jw[k] += c w[k] (<see cref="IJacobianProductTail"/>),
    /// which <see cref="Residual"/> and <see cref="MassMinusJacobian"/> then add to the product they read, on the free
    /// particles, before using it; <paramref name="present"/> false: the products are whole.
    /// </summary>
    public void SetProductTail(bool present, double coefficient)
    {
        _hasTail = present;
        _tail = present ? coefficient : 0.0;
    }

    /// <summary>
    /// r = b - (M dv - jw) on the free particles (jw = J dv, with the product's tail added first), 0 on pinned ones,
    /// then jw = 0; returns r . r.
    /// </summary>
    public double Residual() => Run(ResidualPass);

    /// <summary>
    /// z . w with w = M z - jw on the free particles (jw = J z, with the product's tail added first and kept), jw = 0
    /// on the pinned ones (w is 0 there); the free particles' jw is left for the update, which computes w from it again
    /// and clears it.
    /// </summary>
    public double MassMinusJacobian() => Run(MassMinusJacobianPass);

    /// <summary>
    /// One step of the iteration and, for block Jacobi, its preconditioner: p = z + beta p, s = w + beta s (w = M z - jw,
    /// then jw = 0), dv += alpha p, r -= alpha s, then z = D^-1 r. Returns r . r; r . z is left in
    /// <see cref="LastJacobiProduct"/>.
    /// </summary>
    public double Update(double alpha, double beta)
    {
        _scalar = alpha;
        _secondScalar = beta;
        var rr = Run(UpdatePass);
        LastJacobiProduct = Chunk.Sum(_secondPartial);
        return rr;
    }

    /// <summary>z = D^-1 r with the inverted diagonal blocks; returns r . z.</summary>
    public double Jacobi() => Run(JacobiPass);

    /// <summary>
    /// The multigrid's first half on r, B_1 = P^T r with level 1's pre-smoothing (before the first iteration; see
    /// <see cref="AggregationMultigrid.Restrict"/>).
    /// </summary>
    public void Restrict(AggregationMultigrid multigrid) => multigrid.Restrict(R, _inverseMasses, _runner);

    /// <summary>
    /// One step of the iteration fused with the multigrid's first half on the new r
    /// (<see cref="AggregationMultigrid.UpdateAndRestrict"/>); returns r . r.
    /// </summary>
    public double UpdateAndRestrict(AggregationMultigrid multigrid, double alpha, double beta) =>
        multigrid.UpdateAndRestrict(Z, JacobianProduct, _masses, _coordinateMasses, P, S, Dv, R, _inverseMasses, alpha, beta, _runner);

    /// <summary>
    /// The multigrid's second half, z = D^-1 r + P X_1 after the cycle (<see cref="AggregationMultigrid.CycleAndProlong"/>);
    /// returns r . z.
    /// </summary>
    public double CycleAndProlong(AggregationMultigrid multigrid) => multigrid.CycleAndProlong(R, _inverses, _inverseMasses, Z, _runner);

    /// <summary>
    /// Writes D_i^-1 = (M_i - J_ii)^-1 into <see cref="Inverses"/>; a pinned particle gets the zero block (filtered), a
    /// degenerate block plain Jacobi on the mass, 1 / m_i. <see cref="Blocks"/> keeps J_ii.
    /// </summary>
    public void InvertBlocks() => _ = Run(InvertBlocksPass);

    /// <summary>v1 = v0 + dv and x1 = x0 + h v1, for every particle (a pinned one moves at its own velocity).</summary>
    public void EndState(ReadOnlySpan<double> x0, ReadOnlySpan<double> v0, Span<double> x1, Span<double> v1, double h)
    {
        var n = 3L * _particles;
        if (x0.Length < n || v0.Length < n || x1.Length < n || v1.Length < n)
        {
            throw new ArgumentException($"The end state needs {n} positions and velocities.");
        }

        fixed (double* px0 = &System.Runtime.InteropServices.MemoryMarshal.GetReference(x0))
        fixed (double* pv0 = &System.Runtime.InteropServices.MemoryMarshal.GetReference(v0))
        fixed (double* px1 = x1, pv1 = v1)
        {
            _a = px0;
            _b = pv0;
            _c = px1;
            _d = pv1;
            _scalar = h;
            _ = Run(EndStatePass);
        }
    }

    /// <inheritdoc />
    /// <remarks>
    /// Each pass is a method of its own, its vectors' addresses and its sums in locals: in one method with a switch over
    /// the passes, the sums lived on the stack (every addition a store and a load) and the fields were read again after
    /// every store through a pointer.
    /// </remarks>
    public void Execute(int chunk, int chunkCount)
    {
        var (begin, end) = Chunk.Range(chunk, chunkCount, _particles);
        var sum = 0.0;
        var second = 0.0;
        switch (_operation)
        {
            case RightHandSidePass:
                sum = RightHandSideChunk(begin, end);
                break;
            case WarmStartPass:
                WarmStartChunk(begin, end);
                break;
            case WarmStartGramPass:
                WarmStartGramChunk(chunk, begin, end);
                break;
            case SolutionProductPass:
                SolutionProductChunk(begin, end);
                break;
            case ResidualPass:
                sum = ResidualChunk(begin, end);
                break;
            case MassMinusJacobianPass:
                sum = MassMinusJacobianChunk(begin, end);
                break;
            case UpdatePass:
                sum = UpdateChunk(begin, end, out second);
                break;
            case JacobiPass:
                sum = JacobiChunk(begin, end);
                break;
            case InvertBlocksPass:
                for (var i = begin; i < end; i++)
                {
                    InvertBlock(i);
                }

                break;
            default:
                EndStateChunk(begin, end);
                break;
        }

        _partial[chunk] = sum;
        _secondPartial[chunk] = second;
    }

    /// <summary>b = h (f + h jw) on particles [begin, end), 0 on pinned ones, then jw = 0; returns their b . b.</summary>
    private double RightHandSideChunk(int begin, int end)
    {
        double* b = _pB, force = _a, jacobian = _pJw, inverseMasses = _pInverseMasses;
        var h = _scalar;
        var sum = 0.0;
        for (var i = begin; i < end; i++)
        {
            var o = 3 * i;
            double* bi = b + o, f = force + o, jw = jacobian + o;
            if (inverseMasses[i] == 0.0)
            {
                bi[0] = bi[1] = bi[2] = 0.0;
                jw[0] = jw[1] = jw[2] = 0.0;
                continue;
            }

            bi[0] = h * (f[0] + (h * jw[0]));
            bi[1] = h * (f[1] + (h * jw[1]));
            bi[2] = h * (f[2] + (h * jw[2]));
            jw[0] = jw[1] = jw[2] = 0.0;
            sum += bi[0] * bi[0];
            sum += bi[1] * bi[1];
            sum += bi[2] * bi[2];
        }

        return sum;
    }

    /// <summary>
    /// Rows of the warm start's sums for one chunk, u_a . q_0 .. q_{count-1} and u_a . b, in one sweep of the chunk per
    /// two rows: ten sums at a time keep their chains in registers (all of them at once would not), and the chunk's
    /// vectors stay in the cache between the sweeps. Each sum in increasing coordinate order.
    /// </summary>
    private void WarmStartGramChunk(int chunk, int begin, int end)
    {
        var count = _startCount;
        var sums = stackalloc double[10];
        for (var a = 0; a < count; a += 2)
        {
            var rows = Math.Min(2, count - a);
            GramRows(a, rows, begin, end, sums);
            for (var row = 0; row < rows; row++)
            {
                for (var c = 0; c < count; c++)
                {
                    _gramPartials[((a + row) * count) + c][chunk] = sums[(5 * row) + c];
                }

                _gramPartials[(count * count) + a + row][chunk] = sums[(5 * row) + 4];
            }
        }
    }

    /// <summary>q = b - r on particles [begin, end) (q in the pass's first argument), 0 on pinned ones.</summary>
    private void SolutionProductChunk(int begin, int end)
    {
        double* q = _a, b = _pB, r = _pR, inverseMasses = _pInverseMasses;
        for (var k = 3 * begin; k < 3 * end; k++)
        {
            q[k] = inverseMasses[k / 3] == 0.0 ? 0.0 : b[k] - r[k];
        }
    }

    /// <summary>r = b - (M dv - jw) on particles [begin, end) (the tail added to jw first), 0 on pinned ones, then jw = 0; returns their r . r.</summary>
    private double ResidualChunk(int begin, int end)
    {
        double* dv = _pDv, residual = _pR, b = _pB, jacobian = _pJw, masses = _pMasses, inverseMasses = _pInverseMasses;
        bool hasTail = _hasTail;
        var tail = _tail;
        var sum = 0.0;
        for (var i = begin; i < end; i++)
        {
            var o = 3 * i;
            double* x = dv + o, r = residual + o, bi = b + o, jw = jacobian + o;
            if (inverseMasses[i] == 0.0)
            {
                r[0] = r[1] = r[2] = 0.0;
                jw[0] = jw[1] = jw[2] = 0.0;
                continue;
            }

            AddTail(jw, x, hasTail, tail);

            var m = masses[i];
            r[0] = bi[0] - ((m * x[0]) - jw[0]);
            r[1] = bi[1] - ((m * x[1]) - jw[1]);
            r[2] = bi[2] - ((m * x[2]) - jw[2]);
            jw[0] = jw[1] = jw[2] = 0.0;
            sum += r[0] * r[0];
            sum += r[1] * r[1];
            sum += r[2] * r[2];
        }

        return sum;
    }

    /// <summary>
    /// z . w with w = M z - jw on particles [begin, end) (the tail added to jw first and kept there), jw = 0 on pinned
    /// ones; returns the sum.
    /// </summary>
    private double MassMinusJacobianChunk(int begin, int end)
    {
        double* preconditioned = _pZ, jacobian = _pJw, masses = _pMasses, inverseMasses = _pInverseMasses;
        bool hasTail = _hasTail;
        var tail = _tail;
        var sum = 0.0;
        for (var i = begin; i < end; i++)
        {
            var o = 3 * i;
            double* z = preconditioned + o, jw = jacobian + o;
            if (inverseMasses[i] == 0.0)
            {
                jw[0] = jw[1] = jw[2] = 0.0; // (z is 0 here, so the update's w = M z - jw is 0)
                continue;
            }

            AddTail(jw, z, hasTail, tail); // (kept in jw for the update)

            var m = masses[i];
            double wx = (m * z[0]) - jw[0], wy = (m * z[1]) - jw[1], wz = (m * z[2]) - jw[2];
            sum += (z[0] * wx) + (z[1] * wy) + (z[2] * wz);
        }

        return sum;
    }

    /// <summary>The update and block Jacobi on particles [begin, end) (<see cref="Update"/>); returns r . r, and r . z in <paramref name="rz"/>.</summary>
    private double UpdateChunk(int begin, int end, out double rz)
    {
        double* z = _pZ, jw = _pJw, p = _pP, s = _pS, dv = _pDv, r = _pR, inverses = _pInverses, masses = _pMasses;
        double alpha = _scalar, beta = _secondScalar;
        var sum = 0.0;
        var second = 0.0;
        for (var i = begin; i < end; i++)
        {
            var o = 3 * i;
            var mass = masses[i];
            var r0 = ConjugateGradientUpdate.Component(z, jw, mass, p, s, dv, r, alpha, beta, o);
            var r1 = ConjugateGradientUpdate.Component(z, jw, mass, p, s, dv, r, alpha, beta, o + 1);
            var r2 = ConjugateGradientUpdate.Component(z, jw, mass, p, s, dv, r, alpha, beta, o + 2);
            sum += r0 * r0;
            sum += r1 * r1;
            sum += r2 * r2;
            var zi = z + o;
            Blocks3.MultiplySymmetric(inverses + (6 * i), r + o, zi); // z = D^-1 r with the r just written
            second += (r0 * zi[0]) + (r1 * zi[1]) + (r2 * zi[2]);
        }

        rz = second;
        return sum;
    }

    /// <summary>z = D^-1 r on particles [begin, end); returns their r . z.</summary>
    private double JacobiChunk(int begin, int end)
    {
        double* residual = _pR, preconditioned = _pZ, inverses = _pInverses;
        var sum = 0.0;
        for (var i = begin; i < end; i++)
        {
            double* r = residual + (3 * i), z = preconditioned + (3 * i);
            Blocks3.MultiplySymmetric(inverses + (6 * i), r, z);
            sum += (r[0] * z[0]) + (r[1] * z[1]) + (r[2] * z[2]);
        }

        return sum;
    }

    /// <summary>v1 = v0 + dv and x1 = x0 + h v1 on particles [begin, end) (x0, v0, x1, v1 the pass's four arguments).</summary>
    private void EndStateChunk(int begin, int end)
    {
        double* x0 = _a, v0 = _b, x1 = _c, v1 = _d, dv = _pDv;
        var h = _scalar;
        for (var k = 3 * begin; k < 3 * end; k++)
        {
            var v = v0[k] + dv[k];
            v1[k] = v;
            x1[k] = x0[k] + (h * v);
        }
    }

    /// <summary>
    /// dv = c_0 u_0 + ... + c_{count-1} u_{count-1} over particles [begin, end), 0 on pinned ones: one loop per count,
    /// so that each coordinate adds exactly its count terms, in that order.
    /// </summary>
    private void WarmStartChunk(int begin, int end)
    {
        double* u0 = (double*)_startVectors[0], u1 = (double*)_startVectors[1];
        double* u2 = (double*)_startVectors[2], u3 = (double*)_startVectors[3];
        double c0 = _startCoefficients[0], c1 = _startCoefficients[1], c2 = _startCoefficients[2], c3 = _startCoefficients[3];
        var count = _startCount;
        for (var i = begin; i < end; i++)
        {
            long o = 3 * i;
            var dv = _pDv + o;
            if (_pInverseMasses[i] == 0.0)
            {
                dv[0] = dv[1] = dv[2] = 0.0;
                continue;
            }

            for (var k = o; k < o + 3; k++)
            {
                _pDv[k] = count switch
                {
                    1 => c0 * u0[k],
                    2 => (c0 * u0[k]) + (c1 * u1[k]),
                    3 => (c0 * u0[k]) + (c1 * u1[k]) + (c2 * u2[k]),
                    _ => (c0 * u0[k]) + (c1 * u1[k]) + (c2 * u2[k]) + (c3 * u3[k]),
                };
            }
        }
    }

    /// <summary>
    /// Rows a and a + 1 (or row a alone when <paramref name="rows"/> is 1) of the warm start's sums over particles
    /// [<paramref name="begin"/>, <paramref name="end"/>): u_a . q_c for every c and u_a . b, each in increasing
    /// coordinate order, into <paramref name="sums"/> (five per row: the four products, those at c &gt;= count of no use
    /// and read from q_0 again, then b). Two rows at a time so that ten sums run side by side: each sum is a chain of
    /// additions, and five chains at a time left the processor waiting on them (the same sums in the same order, so the
    /// same bits).
    /// </summary>
    private void GramRows(int a, int rows, int begin, int end, double* sums)
    {
        var count = _startCount;
        var u = (double*)_startVectors[a];
        var v = rows > 1 ? (double*)_startVectors[a + 1] : u;
        var q0 = (double*)_startProducts[0];
        var q1 = count > 1 ? (double*)_startProducts[1] : q0;
        var q2 = count > 2 ? (double*)_startProducts[2] : q0;
        var q3 = count > 3 ? (double*)_startProducts[3] : q0;
        double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0, sb = 0.0;
        double t0 = 0.0, t1 = 0.0, t2 = 0.0, t3 = 0.0, tb = 0.0;
        for (var i = begin; i < end; i++)
        {
            if (_pInverseMasses[i] == 0.0)
            {
                continue;
            }

            for (long k = 3 * i; k < (3 * i) + 3; k++)
            {
                double uk = u[k], vk = v[k], q0k = q0[k], q1k = q1[k], q2k = q2[k], q3k = q3[k], bk = _pB[k];
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

    /// <summary>The product's uniform tail at one particle, when there is one, as the force would have added it: jw[k] += c w[k].</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void AddTail(double* jw, double* w, bool hasTail, double tail)
    {
        if (hasTail)
        {
            jw[0] += tail * w[0];
            jw[1] += tail * w[1];
            jw[2] += tail * w[2];
        }
    }

    /// <summary>
    /// D_i^-1 = (M_i - J_ii)^-1 for particle i, by the cofactors of the symmetric block (its upper triangle:
    /// <see cref="Blocks3.InvertSymmetric"/>), stored as its upper triangle.
    /// </summary>
    private void InvertBlock(int i)
    {
        var inverse = _pInverses + (6L * i);
        if (_pInverseMasses[i] == 0.0)
        {
            for (var k = 0; k < 6; k++)
            {
                inverse[k] = 0.0;
            }

            return;
        }

        var m = _pMasses[i];
        var j = _pBlocks + (9L * i);
        if (!Blocks3.InvertSymmetric(m - j[0], -j[1], -j[2], m - j[4], -j[5], m - j[8], inverse))
        {
            // Degenerate block: fall back to plain Jacobi on the mass alone.
            inverse[0] = inverse[3] = inverse[5] = 1.0 / m;
            inverse[1] = inverse[2] = inverse[4] = 0.0;
        }
    }

    /// <summary><paramref name="count"/> arrays of one partial sum per chunk.</summary>
    private static double[][] NewPartials(int count)
    {
        var partials = new double[count][];
        for (var j = 0; j < count; j++)
        {
            partials[j] = new double[AggregationMultigrid.Chunks];
        }

        return partials;
    }

    private double Run(int operation)
    {
        _operation = operation;
        fixed (double* b = B, dv = Dv, r = R, p = P, s = S, z = Z, jw = JacobianProduct, blocks = Blocks)
        fixed (double* masses = _masses, inverseMasses = _inverseMasses, inverses = _inverses)
        {
            _pInverses = inverses;
            _pB = b;
            _pDv = dv;
            _pR = r;
            _pP = p;
            _pS = s;
            _pZ = z;
            _pJw = jw;
            _pBlocks = blocks;
            _pMasses = masses;
            _pInverseMasses = inverseMasses;
            Chunk.RunAll(_runner, this, _partial.Length);
        }

        return Chunk.Sum(_partial);
    }
}
