using System;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Integrators;

/// <summary>
/// The vector passes of implicit Euler's conjugate gradients, in a fixed number of chunks of particles whose partial
/// sums are added in chunk order: the same bits whether the chunks run on one thread or on a runner's several.
/// </summary>
internal sealed unsafe class ConjugateGradientPasses : IParallelWork
{
    private const int DotPass = 0;
    private const int MassMinusJacobianPass = 1;
    private const int UpdatePass = 2;
    private const int JacobiPass = 3;
    private const int DirectionPass = 4;

    private readonly double[] _partial = new double[AggregationMultigrid.Chunks];
    private double[] _masses = Array.Empty<double>();
    private double[] _inverseMasses = Array.Empty<double>();
    private double[] _dv = Array.Empty<double>();
    private double[] _r = Array.Empty<double>();
    private double[] _p = Array.Empty<double>();
    private double[] _q = Array.Empty<double>();
    private double[] _z = Array.Empty<double>();
    private double[] _jw = Array.Empty<double>();
    private double[] _blocks = Array.Empty<double>();
    private IParallelRunner? _runner;

    // The operation of the pass under way and its arguments (pinned for the pass's duration).
    private int _operation;
    private double* _a;
    private double* _b;
    private double _scalar;
    private double* _pDv;
    private double* _pR;
    private double* _pP;
    private double* _pQ;
    private double* _pZ;
    private double* _pJw;
    private double* _pBlocks;
    private double* _pMasses;
    private double* _pInverseMasses;
    private int _particles;

    /// <summary>The system's J w, which <see cref="MassMinusJacobian"/> reads.</summary>
    public double[] JacobianProduct => _jw;

    /// <summary>This step's inverse masses (0 for pinned particles).</summary>
    public Span<double> InverseMasses => _inverseMasses;

    public void Bind(
        double[] dv, double[] r, double[] p, double[] q, double[] z, double[] jw, double[] inverseBlocks,
        Span<double> masses, Span<double> inverseMasses, IParallelRunner? runner)
    {
        // Every pass runs its pointers over 3 values per particle (9 for the blocks): checked here, where they are bound.
        var n = 3L * masses.Length;
        if (inverseMasses.Length != masses.Length || dv.Length < n || r.Length < n || p.Length < n || q.Length < n
            || z.Length < n || jw.Length < n || inverseBlocks.Length < 3 * n)
        {
            throw new ArgumentException(
                $"The conjugate gradients' vectors need {n} values each and the blocks {3 * n} for {masses.Length} particles.");
        }

        if (_masses.Length != masses.Length)
        {
            _masses = new double[masses.Length];
            _inverseMasses = new double[masses.Length];
        }

        masses.CopyTo(_masses);
        inverseMasses.CopyTo(_inverseMasses);
        _dv = dv;
        _r = r;
        _p = p;
        _q = q;
        _z = z;
        _jw = jw;
        _blocks = inverseBlocks;
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

    /// <summary>a . b.</summary>
    public double Dot(double[] a, double[] b)
    {
        CheckLength(a);
        CheckLength(b);
        fixed (double* pa = a, pb = b)
        {
            _a = pa;
            _b = pb;
            return Run(DotPass);
        }
    }

    /// <summary>q = M w - J w on the free particles (J w from <see cref="JacobianProduct"/>), 0 on pinned ones; returns w . q.</summary>
    public double MassMinusJacobian(double[] w)
    {
        CheckLength(w);
        fixed (double* pw = w)
        {
            _a = pw;
            return Run(MassMinusJacobianPass);
        }
    }

    /// <summary>dv += alpha p, r -= alpha q; returns r . r.</summary>
    public double Update(double alpha)
    {
        _scalar = alpha;
        return Run(UpdatePass);
    }

    /// <summary>z = P r with the inverted diagonal blocks; returns r . z.</summary>
    public double Jacobi() => Run(JacobiPass);

    /// <summary>p = z + beta p.</summary>
    public void NewDirection(double beta)
    {
        _scalar = beta;
        _ = Run(DirectionPass);
    }

    public void Execute(int chunk, int chunkCount)
    {
        var (begin, end) = Chunk.Range(chunk, chunkCount, _particles);
        var sum = 0.0;
        switch (_operation)
        {
            case DotPass:
                for (var k = 3 * begin; k < 3 * end; k++)
                {
                    sum += _a[k] * _b[k];
                }

                break;
            case MassMinusJacobianPass:
                for (var i = begin; i < end; i++)
                {
                    var o = 3 * i;
                    double* w = _a + o, q = _pQ + o, jw = _pJw + o;
                    if (_pInverseMasses[i] == 0.0)
                    {
                        q[0] = q[1] = q[2] = 0.0;
                        continue;
                    }

                    var m = _pMasses[i];
                    double qx = (m * w[0]) - jw[0], qy = (m * w[1]) - jw[1], qz = (m * w[2]) - jw[2];
                    q[0] = qx;
                    q[1] = qy;
                    q[2] = qz;
                    sum += (w[0] * qx) + (w[1] * qy) + (w[2] * qz);
                }

                break;
            case UpdatePass:
                for (var k = 3 * begin; k < 3 * end; k++)
                {
                    _pDv[k] += _scalar * _pP[k];
                    var rk = _pR[k] - (_scalar * _pQ[k]);
                    _pR[k] = rk;
                    sum += rk * rk;
                }

                break;
            case JacobiPass:
                for (var i = begin; i < end; i++)
                {
                    double* r = _pR + (3 * i), z = _pZ + (3 * i), m = _pBlocks + (9 * i);
                    double rx = r[0], ry = r[1], rz = r[2];
                    var zx = (m[0] * rx) + (m[1] * ry) + (m[2] * rz);
                    var zy = (m[3] * rx) + (m[4] * ry) + (m[5] * rz);
                    var zz = (m[6] * rx) + (m[7] * ry) + (m[8] * rz);
                    z[0] = zx;
                    z[1] = zy;
                    z[2] = zz;
                    sum += (rx * zx) + (ry * zy) + (rz * zz);
                }

                break;
            default:
                for (var k = 3 * begin; k < 3 * end; k++)
                {
                    _pP[k] = _pZ[k] + (_scalar * _pP[k]);
                }

                break;
        }

        _partial[chunk] = sum;
    }

    private double Run(int operation)
    {
        _operation = operation;
        fixed (double* dv = _dv, r = _r, p = _p, q = _q, z = _z, jw = _jw, blocks = _blocks, masses = _masses, inverseMasses = _inverseMasses)
        {
            _pDv = dv;
            _pR = r;
            _pP = p;
            _pQ = q;
            _pZ = z;
            _pJw = jw;
            _pBlocks = blocks;
            _pMasses = masses;
            _pInverseMasses = inverseMasses;
            var chunks = _partial.Length;
            if (_runner is not null)
            {
                _runner.Run(this, chunks);
            }
            else
            {
                for (var c = 0; c < chunks; c++)
                {
                    Execute(c, chunks);
                }
            }
        }

        var total = 0.0;
        for (var c = 0; c < _partial.Length; c++)
        {
            total += _partial[c];
        }

        return total;
    }
}
