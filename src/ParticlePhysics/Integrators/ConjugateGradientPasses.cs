using System;
using System.Runtime.CompilerServices;
using ParticlePhysics.Integrators.Multigrid;
using ParticlePhysics.Internal;
using ParticlePhysics.Numerics;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Integrators;

/// <summary>
/// The vectors of implicit Euler's conjugate gradients (Chronopoulos and Gear's form, see <see cref="ImplicitEuler"/>)
/// and the passes over them, each a class of its own set with exactly the vectors it reads and writes, in a fixed
/// number of chunks of particles whose partial sums are added in chunk order: the same bits whether the chunks run on
/// one thread or on a runner's several. The passes are grouped by when they run: the warm start
/// (ConjugateGradientPasses.WarmStart.cs), the rest of what comes before the iterations (.Start.cs), each iteration
/// (.Iteration.cs) and what comes after them (.End.cs).
/// </summary>
/// <remarks>
/// The vectors, 3 values per particle: b the right-hand side, dv the solution, r = b - A dv the residual, z = P r the
/// preconditioned residual, p the search direction and s = A p; jw receives the system's J times a vector (without
/// its uniform tail c w when the system has one, which the residual and z . w passes add before they use jw: see
/// <see cref="SetProductTail"/>), and the pass that reads it last leaves it 0 for the next product (no pass of its own
/// clears it). w = A z = M z - J z is never stored: the pass after the product sums z . w from z and jw (and leaves
/// jw), and the update, which needs w once, computes it again from the same two (the same operations, so the same
/// bits as a stored w) and clears jw, which saves writing and re-reading a vector every iteration; the blocks (9
/// values per particle) are J_ii, and <see cref="InvertBlocks"/> writes D_i^-1 = (M_i - J_ii)^-1 into the inverses,
/// 6 values per particle: the matrix is symmetric, so its upper triangle xx, xy, xz, yy, yz, zz is all of it, and the
/// passes that apply it every iteration read two thirds of the bytes. A pinned particle's components are 0 in every
/// vector but dv's warm start (filtered there too). Each pass's loop is a method of its own with its addresses and
/// sums in locals, where the JIT keeps them in registers (a field is read again after every store through a pointer).
/// </remarks>
internal sealed unsafe partial class ConjugateGradientPasses
{
    /// <summary>The chunks of every pass: the multigrid's, so that a thread finds its chunk's vectors in its cache.</summary>
    private const int Chunks = AggregationMultigrid.Chunks;

    private bool _hasTail; // whether this step's products leave out a uniform last term c w (SetProductTail), and c
    private double _tail;
    private double[] _masses = Array.Empty<double>();
    private double[] _coordinateMasses = Array.Empty<double>();
    private double[] _inverses = Array.Empty<double>();
    private double[] _inverseMasses = Array.Empty<double>();
    private IParallelRunner? _runner;
    private int _particles;

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

    private void CheckLength(double[] values)
    {
        if (values.Length < 3L * _particles)
        {
            throw new ArgumentException($"A vector of the conjugate gradients needs {3L * _particles} values; it has {values.Length}.");
        }
    }

    /// <summary>Runs a pass in <see cref="Chunks"/> chunks, on the runner when there is one.</summary>
    private void Run(IParallelWork pass) => Chunk.RunAll(_runner, pass, Chunks);

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
}
