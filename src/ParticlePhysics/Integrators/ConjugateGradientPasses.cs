using System;
using System.Runtime.CompilerServices;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Integrators;

/// <summary>
/// The vector passes of implicit Euler's conjugate gradients (Chronopoulos and Gear's form, see
/// <see cref="ImplicitEuler"/>), in a fixed number of chunks of particles whose partial sums are added in chunk order:
/// the same bits whether the chunks run on one thread or on a runner's several.
/// </summary>
/// <remarks>
/// The vectors, 3 values per particle: b the right-hand side, dv the solution, r = b - A dv the residual, z = P r the
/// preconditioned residual, p the search direction and s = A p; jw receives the system's J times a vector, and the
/// passes that read it leave it 0 for the next product (no pass of its own clears it). w = A z = M z - J z is never
/// stored: the pass after the product sums z . w from z and jw, and the update, which needs w once, computes it again
/// from the same two (the same operations, so the same bits as a stored w), which saves writing and re-reading a
/// vector every iteration; the blocks (9 values
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
    // The six sums of WarmStartGram, each per chunk: u1 . q1, u1 . q2, u2 . q1, u2 . q2, u1 . b, u2 . b.
    private readonly double[][] _gramPartials = NewPartials(6);
    private double[] _masses = Array.Empty<double>();
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

    /// <summary>The system's J times a vector, which <see cref="Residual"/>, <see cref="MassMinusJacobian"/> and the update read.</summary>
    public double[] JacobianProduct { get; private set; } = Array.Empty<double>();

    /// <summary>The diagonal blocks J_ii (9 values per particle, row-major), as the forces added them.</summary>
    public double[] Blocks { get; private set; } = Array.Empty<double>();

    /// <summary>
    /// D_i^-1 = (M_i - J_ii)^-1 after <see cref="InvertBlocks"/>, 6 values per particle: the upper triangle
    /// xx, xy, xz, yy, yz, zz of the symmetric block (<see cref="Blocks3.MultiplySymmetric"/> applies it).
    /// </summary>
    public double[] Inverses => _inverses;

    /// <summary>This step's masses, a copy the passes own.</summary>
    public double[] Masses => _masses;

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
        // Every pass runs its pointers over 3 values per particle (9 for the blocks): checked here, where they are bound.
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
            _inverseMasses = new double[masses.Length];
            _inverses = new double[6 * masses.Length];
        }

        masses.CopyTo(_masses);
        inverseMasses.CopyTo(_inverseMasses);
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
    /// dv = c1 last + c2 previous (or c1 last when <paramref name="previous"/> is null) on the free particles, 0 on
    /// pinned ones: the warm start from the last two steps' dv (c1 = 2, c2 = -1 is their linear extrapolation).
    /// </summary>
    public void WarmStart(double[] last, double[]? previous, double c1, double c2)
    {
        CheckLength(last);
        if (previous is not null)
        {
            CheckLength(previous);
        }

        fixed (double* l = last, q = previous)
        {
            _a = l;
            _b = q;
            _scalar = c1;
            _secondScalar = c2;
            _ = Run(WarmStartPass);
        }
    }

    /// <summary>
    /// The sums that choose the warm start in the plane of the last two steps' dv, u1 = last and u2 = previous, from
    /// their products q1 ~ A u1 and q2 ~ A u2 (each step's b - r at its end), over the free particles: u1 . q1,
    /// u1 . q2, u2 . q1, u2 . q2, u1 . b and u2 . b, each summed in chunk order (the u2 sums are 0 without a previous
    /// step). Needs b.
    /// </summary>
    public (double U1Q1, double U1Q2, double U2Q1, double U2Q2, double U1B, double U2B) WarmStartGram(
        double[] last, double[] lastProduct, double[]? previous, double[]? previousProduct)
    {
        CheckLength(last);
        CheckLength(lastProduct);
        if ((previous is null) != (previousProduct is null))
        {
            throw new ArgumentException("The previous step's dv and its product come together.");
        }

        if (previous is not null)
        {
            CheckLength(previous);
            CheckLength(previousProduct!);
        }

        fixed (double* u1 = last, q1 = lastProduct, u2 = previous, q2 = previousProduct)
        {
            _a = u1;
            _b = u2;
            _c = q1;
            _d = q2;
            _ = Run(WarmStartGramPass);
        }

        var g = _gramPartials;
        return (Chunk.Sum(g[0]), Chunk.Sum(g[1]), Chunk.Sum(g[2]), Chunk.Sum(g[3]), Chunk.Sum(g[4]), Chunk.Sum(g[5]));
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

    /// <summary>r = b - (M dv - jw) on the free particles (jw = J dv), 0 on pinned ones, then jw = 0; returns r . r.</summary>
    public double Residual() => Run(ResidualPass);

    /// <summary>
    /// z . w with w = M z - jw on the free particles (jw = J z), jw = 0 on the pinned ones (w is 0 there); the free
    /// particles' jw is left for the update, which computes w from it again and clears it.
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

    public void Execute(int chunk, int chunkCount)
    {
        var (begin, end) = Chunk.Range(chunk, chunkCount, _particles);
        var sum = 0.0;
        var second = 0.0;
        switch (_operation)
        {
            case RightHandSidePass:
                for (var i = begin; i < end; i++)
                {
                    var o = 3 * i;
                    double* bi = _pB + o, f = _a + o, jw = _pJw + o;
                    if (_pInverseMasses[i] == 0.0)
                    {
                        bi[0] = bi[1] = bi[2] = 0.0;
                        jw[0] = jw[1] = jw[2] = 0.0;
                        continue;
                    }

                    var h = _scalar;
                    bi[0] = h * (f[0] + (h * jw[0]));
                    bi[1] = h * (f[1] + (h * jw[1]));
                    bi[2] = h * (f[2] + (h * jw[2]));
                    jw[0] = jw[1] = jw[2] = 0.0;
                    sum += bi[0] * bi[0];
                    sum += bi[1] * bi[1];
                    sum += bi[2] * bi[2];
                }

                break;
            case WarmStartPass:
                for (var i = begin; i < end; i++)
                {
                    var o = 3 * i;
                    double* dv = _pDv + o, last = _a + o;
                    if (_pInverseMasses[i] == 0.0)
                    {
                        dv[0] = dv[1] = dv[2] = 0.0;
                    }
                    else if (_b is null)
                    {
                        dv[0] = _scalar * last[0];
                        dv[1] = _scalar * last[1];
                        dv[2] = _scalar * last[2];
                    }
                    else
                    {
                        var previous = _b + o;
                        dv[0] = (_scalar * last[0]) + (_secondScalar * previous[0]);
                        dv[1] = (_scalar * last[1]) + (_secondScalar * previous[1]);
                        dv[2] = (_scalar * last[2]) + (_secondScalar * previous[2]);
                    }
                }

                break;
            case WarmStartGramPass:
                {
                    double u1q1 = 0, u1q2 = 0, u2q1 = 0, u2q2 = 0, u1b = 0, u2b = 0;
                    var two = _b is not null;
                    for (var i = begin; i < end; i++)
                    {
                        if (_pInverseMasses[i] == 0.0)
                        {
                            continue;
                        }

                        for (var k = 3 * i; k < (3 * i) + 3; k++)
                        {
                            double a1 = _a[k], c1 = _c[k], bk = _pB[k];
                            u1q1 += a1 * c1;
                            u1b += a1 * bk;
                            if (two)
                            {
                                double a2 = _b[k], c2 = _d[k];
                                u1q2 += a1 * c2;
                                u2q1 += a2 * c1;
                                u2q2 += a2 * c2;
                                u2b += a2 * bk;
                            }
                        }
                    }

                    var g = _gramPartials;
                    (g[0][chunk], g[1][chunk], g[2][chunk], g[3][chunk], g[4][chunk], g[5][chunk]) = (u1q1, u1q2, u2q1, u2q2, u1b, u2b);
                    break;
                }

            case SolutionProductPass:
                for (var k = 3 * begin; k < 3 * end; k++)
                {
                    _a[k] = _pInverseMasses[k / 3] == 0.0 ? 0.0 : _pB[k] - _pR[k];
                }

                break;
            case ResidualPass:
                for (var i = begin; i < end; i++)
                {
                    var o = 3 * i;
                    double* x = _pDv + o, r = _pR + o, bi = _pB + o, jw = _pJw + o;
                    if (_pInverseMasses[i] == 0.0)
                    {
                        r[0] = r[1] = r[2] = 0.0;
                        jw[0] = jw[1] = jw[2] = 0.0;
                        continue;
                    }

                    var m = _pMasses[i];
                    r[0] = bi[0] - ((m * x[0]) - jw[0]);
                    r[1] = bi[1] - ((m * x[1]) - jw[1]);
                    r[2] = bi[2] - ((m * x[2]) - jw[2]);
                    jw[0] = jw[1] = jw[2] = 0.0;
                    sum += r[0] * r[0];
                    sum += r[1] * r[1];
                    sum += r[2] * r[2];
                }

                break;
            case MassMinusJacobianPass:
                for (var i = begin; i < end; i++)
                {
                    var o = 3 * i;
                    double* z = _pZ + o, jw = _pJw + o;
                    if (_pInverseMasses[i] == 0.0)
                    {
                        jw[0] = jw[1] = jw[2] = 0.0; // (z is 0 here, so the update's w = M z - jw is 0)
                        continue;
                    }

                    var m = _pMasses[i];
                    double wx = (m * z[0]) - jw[0], wy = (m * z[1]) - jw[1], wz = (m * z[2]) - jw[2];
                    sum += (z[0] * wx) + (z[1] * wy) + (z[2] * wz);
                }

                break;
            case UpdatePass:
                for (var i = begin; i < end; i++)
                {
                    var o = 3 * i;
                    double* m = _pInverses + (6 * i);
                    var mass = _pMasses[i];
                    var r0 = UpdateComponent(_pZ, _pJw, mass, _pP, _pS, _pDv, _pR, _scalar, _secondScalar, o);
                    var r1 = UpdateComponent(_pZ, _pJw, mass, _pP, _pS, _pDv, _pR, _scalar, _secondScalar, o + 1);
                    var r2 = UpdateComponent(_pZ, _pJw, mass, _pP, _pS, _pDv, _pR, _scalar, _secondScalar, o + 2);
                    sum += r0 * r0;
                    sum += r1 * r1;
                    sum += r2 * r2;
                    var z = _pZ + o;
                    Blocks3.MultiplySymmetric(m, _pR + o, z); // z = D^-1 r with the r just written
                    second += (r0 * z[0]) + (r1 * z[1]) + (r2 * z[2]);
                }

                break;
            case JacobiPass:
                for (var i = begin; i < end; i++)
                {
                    double* r = _pR + (3 * i), z = _pZ + (3 * i);
                    Blocks3.MultiplySymmetric(_pInverses + (6 * i), r, z);
                    sum += (r[0] * z[0]) + (r[1] * z[1]) + (r[2] * z[2]);
                }

                break;
            case InvertBlocksPass:
                for (var i = begin; i < end; i++)
                {
                    InvertBlock(i);
                }

                break;
            default:
                for (var k = 3 * begin; k < 3 * end; k++)
                {
                    var v1 = _b[k] + _pDv[k];
                    _d[k] = v1;
                    _c[k] = _a[k] + (_scalar * v1);
                }

                break;
        }

        _partial[chunk] = sum;
        _secondPartial[chunk] = second;
    }

    /// <summary>
    /// One component k of the iteration's update, p = z + beta p, s = w + beta s with w = M z - jw (the value that
    /// <see cref="MassMinusJacobian"/> summed; jw is then cleared for the next product), dv += alpha p, r -= alpha s;
    /// returns the new r. Shared with the multigrid's pass that fuses the update with its restriction.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static double UpdateComponent(
        double* z, double* jw, double mass, double* p, double* s, double* dv, double* r, double alpha, double beta, long k)
    {
        var zk = z[k];
        var wk = (mass * zk) - jw[k];
        jw[k] = 0.0;
        var pk = zk + (beta * p[k]);
        p[k] = pk;
        var sk = wk + (beta * s[k]);
        s[k] = sk;
        dv[k] += alpha * pk;
        var rk = r[k] - (alpha * sk);
        r[k] = rk;
        return rk;
    }

    /// <summary>
    /// D_i^-1 = (M_i - J_ii)^-1 for particle i, by cofactors (<see cref="Blocks3.Invert(double*, double*)"/>), stored
    /// as its upper triangle. The cofactors of a symmetric block are symmetric to the last bit (each pair is the same
    /// two products), so the upper triangle is the inverse exactly as the full block held it.
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
        var block = stackalloc double[9];
        for (var k = 0; k < 9; k++)
        {
            block[k] = -j[k];
        }

        block[0] += m;
        block[4] += m;
        block[8] += m;
        if (!Blocks3.Invert(block, block))
        {
            // Degenerate block: fall back to plain Jacobi on the mass alone.
            inverse[0] = inverse[3] = inverse[5] = 1.0 / m;
            inverse[1] = inverse[2] = inverse[4] = 0.0;
            return;
        }

        Blocks3.PackSymmetric(block, inverse);
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
