using System;
using ParticlePhysics.Integrators.Multigrid;
using ParticlePhysics.Internal;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Integrators;

/// <summary>
/// Implicit (backward) Euler: x and v at t + h from the forces at t + h. Unconditionally stable, and dissipative:
/// it keeps a stiff cloth stable at one step per 60 Hz frame where explicit methods blow up.
/// </summary>
/// <remarks>
/// Backward Euler: v1 = v0 + h M^-1 f(x1, v1), x1 = x0 + h v1. For a particle system the force is linearised once
/// per step (Baraff and Witkin, "Large Steps in Cloth Simulation", 1998): with f(x0 + dx, v0 + dv) ~ f0 + K dx + D dv,
/// K = df/dx, D = df/dv and dx = h (v0 + dv), the update dv solves
/// (M - h D - h^2 K) dv = h (f0 + h K v0); then v1 = v0 + dv and x1 = x0 + h v1.
/// The matrix is symmetric positive definite when K and D are symmetric negative semi-definite (springs clamp their
/// compressed transverse stiffness for that); it is solved matrix-free by conjugate gradients with a 3 x 3
/// block-Jacobi preconditioner, pinned particles filtered out (their dv is 0). For forces that are linear in x and v
/// (zero-rest-length springs, drag, dampers, gravity) the linearisation is exact and so is the step (up to the
/// solver's tolerance). For free fall with drag it is the course's v(i+1) = (v(i) - g h) / (1 + h / tau).
/// The stepper sees the forces only through <see cref="ILinearizableSystem"/> (the particle world implements it).
/// For any other <see cref="IOdeSystem"/>, y1 = y0 + h f(t + h, y1) is solved by Newton's method with a
/// finite-difference Jacobian and a dense LU factorisation (fine for small systems such as the course's scalar ODE).
/// Order 1. Stability: the whole left half-plane (A-stable), so any h is stable on a damped linear system.
/// </remarks>
public sealed partial class ImplicitEuler : IStatefulIntegrator
{
    private double _tolerance = 1e-6;
    private int _maxIterations = 200;

    // Warm start, as of the last committed step (IStatefulIntegrator): the last steps' dv and their products with
    // their steps' matrices. A step solves into the history's scratch pair; CommitStep makes it the newest.
    private readonly WarmStartHistory _history = new();
    private readonly double[][] _startVectors = new double[WarmStartHistory.Depth][];
    private readonly double[][] _startProducts = new double[WarmStartHistory.Depth][];
    private readonly double[] _startCoefficients = new double[WarmStartHistory.Depth];
    private readonly double[] _gram = new double[WarmStartHistory.Depth * WarmStartHistory.Depth];
    private readonly double[] _projections = new double[WarmStartHistory.Depth];
    private readonly double[] _elimination = new double[WarmStartHistory.Depth * WarmStartHistory.Depth];
    private readonly int[] _eliminationPivots = new int[WarmStartHistory.Depth];

    // Particle-system path: 3 N values each, except the 9 N preconditioner blocks.
    private double[]? _force;
    private double[]? _rhs;
    private double[]? _residual;
    private double[]? _direction;
    private double[]? _directionProduct;
    private double[]? _preconditioned;
    private double[]? _jacobianProduct;
    private double[]? _blocks;
    private ConjugateGradientPasses? _passes;
    private AggregationMultigrid? _multigrid;

    /// <inheritdoc />
    public string Name => "implicit-euler";

    /// <inheritdoc />
    public int Order => 1;

    /// <summary>
    /// The relative tolerance of the linear solve: conjugate gradients stop when the residual's norm is at most this
    /// fraction of the right-hand side's (default 1e-6). (Newton's method on a plain ODE iterates to 1e-12.)
    /// </summary>
    public double Tolerance
    {
        get => _tolerance;
        set
        {
            Guard.PositiveFinite(value, nameof(Tolerance));
            _tolerance = value;
        }
    }

    /// <summary>The most conjugate-gradient (or Newton) iterations per step (default 200).</summary>
    public int MaxIterations
    {
        get => _maxIterations;
        set
        {
            if (value < 1)
            {
                throw new ArgumentOutOfRangeException(
                    nameof(MaxIterations), value, $"MaxIterations must be at least 1; got {value}.");
            }

            _maxIterations = value;
        }
    }

    /// <summary>
    /// When true, a step whose solve does not reach <see cref="Tolerance"/> within <see cref="MaxIterations"/>
    /// throws <see cref="SolverNotConvergedException"/> (and the system is not advanced). When false (the default)
    /// the step ends with the solver's best solution, and <see cref="LastConverged"/> says it fell short.
    /// </summary>
    public bool ThrowIfNotConverged { get; set; }

    /// <summary>
    /// The preconditioner of the conjugate gradients (default <see cref="ImplicitPreconditioner.Multigrid"/>, which
    /// falls back to block Jacobi on systems of fewer than <see cref="MultigridThreshold"/> particles or without couplings).
    /// </summary>
    public ImplicitPreconditioner Preconditioner { get; set; } = ImplicitPreconditioner.Multigrid;

    /// <summary>Below this many particles the multigrid is not built: block Jacobi costs less there.</summary>
    public const int MultigridThreshold = 64;

    /// <summary>Whether the solve starts from the previous step's velocity change (default true).</summary>
    public bool WarmStart { get; set; } = true;

    /// <summary>How force generators without a Jacobian (<see cref="IForceJacobian"/>) are treated (default explicitly).</summary>
    public UserForceTreatment UserForces { get; set; } = UserForceTreatment.Explicit;

    /// <summary>The iterations the last step's solve took.</summary>
    public int LastIterations { get; private set; }

    /// <summary>The last step's final relative residual (|r| / |b| for conjugate gradients, the last Newton update's relative size for Newton).</summary>
    public double LastResidual { get; private set; }

    /// <summary>True when the last step's solve reached <see cref="Tolerance"/>.</summary>
    public bool LastConverged { get; private set; } = true;

    /// <inheritdoc />
    /// <remarks>
    /// The warm start, so that a restored run continues bit for bit: the last steps' dv and their products (up to
    /// four steps; the format in <see cref="WarmStartHistory"/>). The state of the library before the history was
    /// deeper than two steps, [k + 3 p] and k + p vectors, reads as it was written.
    /// </remarks>
    public int StateLength => _history.StateLength;

    /// <inheritdoc />
    public void WriteState(Span<double> destination) => _history.WriteState(destination);

    /// <inheritdoc />
    public void ReadState(ReadOnlySpan<double> source) => _history.ReadState(source);

    /// <inheritdoc />
    /// <remarks>The warm start of the step just taken, if any, becomes the newest the next step starts from.</remarks>
    public void CommitStep() => _history.Commit();

    /// <inheritdoc />
    public void DiscardStep() => _history.Discard();

    /// <inheritdoc />
    /// <exception cref="SimulationDivergedException">
    /// A force, the implicit system's right-hand side or its solve is not finite (a force that writes NaN or
    /// infinity, or a step so large that h^2 times the stiffness overflows): the step cannot be taken.
    /// </exception>
    public void Step(IOdeSystem system, double time, ReadOnlySpan<double> state, Span<double> next, double dt)
    {
        StepChecks.Check(system, state, next, dt);
        _history.Discard();
        if (system is ILinearizableSystem linearizable)
        {
            StepLinearized(linearizable, time, state, next, dt);
        }
        else
        {
            StepNewton(system, time, state, next, dt);
        }

        if (!LastConverged && ThrowIfNotConverged)
        {
            _history.Discard();
            throw new SolverNotConvergedException(
                time + dt, LastIterations, LastResidual, system is ILinearizableSystem ? _tolerance : NewtonTolerance);
        }
    }

    private void StepLinearized(ILinearizableSystem system, double time, ReadOnlySpan<double> state, Span<double> next, double h)
    {
        var n = system.CoordinateCount;
        var y0 = state.ForReading();
        var x0 = y0.Slice(0, n);
        var v0 = y0.Slice(n, n);
        var f0 = _force = StepChecks.Sized(_force, n);
        var b = _rhs = StepChecks.Sized(_rhs, n);
        var (dv, product) = _history.Scratch(n);
        var r = _residual = StepChecks.Sized(_residual, n);
        var p = _direction = StepChecks.Sized(_direction, n);
        var s = _directionProduct = StepChecks.Sized(_directionProduct, n);
        var z = _preconditioned = StepChecks.Sized(_preconditioned, n);
        var jw = _jacobianProduct = StepChecks.Sized(_jacobianProduct, n);
        var blocks = _blocks = StepChecks.Sized(_blocks, 3 * n);
        var masses = system.Masses.ForReading();
        var inverseMasses = system.InverseMasses.ForReading();
        var runner = system.Runner is { MaxParallelism: > 1 } parallel ? parallel : null;
        var end = time + h;

        // f0, and the linearisation, in one call (one pass over a spring network): K v0 accumulates into jw, the
        // diagonal blocks of h D + h^2 K into blocks.
        Array.Clear(jw, 0, n);
        Array.Clear(blocks, 0, blocks.Length);
        system.AccumulateForcesAndLinearize(end, x0, v0, h * h, h, UserForces, jw, blocks).CopyTo(f0);

        // b = h (f0 + h K v0), filtered; the multigrid's coarse levels from the same linearisation (from the blocks
        // J_ii, which the inversion leaves as they are); block Jacobi P = inverse of the blocks of M - (h D + h^2 K).
        var passes = _passes ??= new ConjugateGradientPasses();
        passes.Bind(b, dv, r, p, s, z, jw, blocks, masses, inverseMasses, runner);

        // A product that ends with a uniform term c w (a drag on every particle, after the springs) leaves that term to
        // the passes that read the product (IJacobianProductTail): one pass over the vectors less per product, and on a
        // runner no pass on the calling thread alone.
        var tailCoefficient = 0.0;
        var tail = system is IJacobianProductTail split && split.TryGetUniformTail(out tailCoefficient) ? split : null;
        passes.SetProductTail(tail is not null, tailCoefficient);
        var rhsNorm = Math.Sqrt(passes.RightHandSide(f0, h));
        if (!DoubleChecks.IsFinite(rhsNorm))
        {
            // A finite |b|^2 is a sum of finite squares, so every b_i = h (f_i + h (K v)_i) of a free particle, and
            // with it f_i, is finite: only a norm that is not finite needs the search for its cause (a force, then b).
            CheckFinite(f0, inverseMasses, time, end, "the force on particle {0} is {1}: a force generator wrote a value that is not finite");
            CheckFinite(b, inverseMasses, time, end, "the implicit system's right-hand side h (f + h K v) at particle {0} is {1}: the step is too large for these forces");
            throw Diverged(time, end, 0, rhsNorm, "the norm of the implicit system's right-hand side overflows: the step is too large for these forces");
        }

        var multigrid = Preconditioner == ImplicitPreconditioner.Multigrid && n >= 3 * MultigridThreshold;
        if (multigrid)
        {
            _multigrid ??= new AggregationMultigrid();
            _multigrid.Setup(system, blocks, masses, inverseMasses, runner);
            multigrid = _multigrid.HasCoarseLevels;
        }

        passes.InvertBlocks();

        // Preconditioned conjugate gradients. Motion is smooth, so dv changes little from step to step: start from
        // the last steps' dv u_0, u_1, ... (newest first), else from 0. Any start converges to the same tolerance; a
        // good one halves the iterations. Under block Jacobi: the linear extrapolation 2 u_0 - u_1 (or u_0). Under the
        // multigrid, with the products q_a ~ A u_a that the last solves left behind (each one's b - r, with its own
        // step's matrix: no product is spent here), the start sum c_a u_a in the span of the last four that satisfies
        // the Galerkin conditions u_j . (b - sum c_a q_a) = 0 (one pass for the sums, a 4 x 4 solve; fewer steps when
        // the system is singular, the extrapolation when none is left): it removes the error in the span of those
        // steps, where the smooth part of the motion lies. Not under block Jacobi: the error it removes there is in the
        // stiff components, which block Jacobi damps anyway (docs/benchmarks.md, "The warm start" and "The warm start
        // from the last four steps"). Pinned components are always 0. The committed warm start is only read here: a
        // step that fails leaves it as it was (CommitStep moves dv and its product in).
        var known = WarmStart && _history.Length == n ? _history.Known : 0;
        var knownProducts = known > 0 ? Math.Min(_history.KnownProducts, known) : 0;
        // The start from the products is the multigrid's, so only its steps keep their products; taken before the
        // solve, which may fall back to block Jacobi on the way.
        var keepProduct = multigrid;
        double rr;
        if (known > 0)
        {
            var count = multigrid && knownProducts > 0 ? StartInSpan(passes, knownProducts) : 0;
            if (count == 0)
            {
                count = Math.Min(2, known);
                _startCoefficients[0] = count > 1 ? 2.0 : 1.0;
                _startCoefficients[1] = -1.0;
            }

            for (var a = 0; a < count; a++)
            {
                _startVectors[a] = _history.Dv(a);
            }

            passes.WarmStart(_startVectors, _startCoefficients, count);
            AddProduct(system, tail, dv, jw); // (jw is 0: the right-hand side's pass cleared it as it read it)
            rr = passes.Residual();
        }
        else
        {
            Array.Clear(dv, 0, n);
            Array.Copy(b, r, n);
            rr = rhsNorm * rhsNorm;
        }

        // Chronopoulos and Gear's form of the iteration ("s-step methods for the conjugate gradient method", 1989): the
        // same iterates as the textbook form in exact arithmetic, with s = A p carried by the recurrence
        // s = w + beta s from w = A z, so that each iteration applies A to the preconditioned residual z as soon as it
        // is known and both scalars come from one product:
        //   gamma = r . z, delta = z . w, beta = gamma / gamma_old, alpha = gamma / (delta - beta gamma / alpha_old)
        //   p = z + beta p, s = w + beta s, dv += alpha p, r -= alpha s
        // (delta - beta gamma / alpha_old is p . A p). The update is one pass over the vectors, fused with the
        // preconditioner's first pass (block Jacobi's z = D^-1 r, or the multigrid's restriction), which halves the
        // passes over the vectors and the hand-offs to a runner per iteration. w = M z - J z is not stored: delta's pass
        // reads z and jw = J z, and the update computes w from them again (a vector less written and read back).
        Array.Clear(p, 0, n);
        Array.Clear(s, 0, n);
        var iterations = 0;
        var residualNorm = Math.Sqrt(rr);
        var target = _tolerance * rhsNorm;
        if (residualNorm > target && _maxIterations > 0)
        {
            var gamma = Precondition(passes, ref multigrid);
            var delta = ApplySystemMatrix(system, tail, passes, time, end);
            var alpha = gamma / delta;
            var beta = 0.0;
            while (delta > 0.0)
            {
                residualNorm = Math.Sqrt(multigrid ? passes.UpdateAndRestrict(_multigrid!, alpha, beta) : passes.Update(alpha, beta));
                iterations++;
                if (residualNorm <= target || iterations >= _maxIterations || !DoubleChecks.IsFinite(residualNorm))
                {
                    break;
                }

                var gammaNext = multigrid ? passes.CycleAndProlong(_multigrid!) : passes.LastJacobiProduct;
                var restart = false;
                if (multigrid && !(gammaNext > 0.0))
                {
                    // The multigrid lost positivity along r: continue with block Jacobi, restarting the directions.
                    multigrid = false;
                    gammaNext = passes.Jacobi();
                    restart = true;
                }

                delta = ApplySystemMatrix(system, tail, passes, time, end);
                beta = restart ? 0.0 : gammaNext / gamma;
                delta -= restart ? 0.0 : beta * gammaNext / alpha; // p . A p for the next direction
                alpha = gammaNext / delta;
                gamma = gammaNext;
            }
        }

        LastIterations = iterations;
        LastResidual = rhsNorm > 0.0 ? residualNorm / rhsNorm : 0.0;
        LastConverged = residualNorm <= target;
        CheckFinite(dv, inverseMasses, time, end, "the implicit solve's velocity change at particle {0} is {1}");
        if (!DoubleChecks.IsFinite(residualNorm))
        {
            LastConverged = false;
            throw Diverged(time, end, 0, residualNorm, "the implicit solve's residual is not finite");
        }

        // Block Jacobi reads only the last two steps' dv (their extrapolation), so only the multigrid's steps keep more.
        var pendingKnown = Math.Min(keepProduct ? WarmStartHistory.Depth : 2, known + 1);
        _history.SetPending(pendingKnown, keepProduct ? Math.Min(pendingKnown, knownProducts + 1) : 0);
        if (keepProduct)
        {
            passes.SolutionProduct(product);
        }

        passes.EndState(x0, v0, next.Slice(0, n), next.Slice(n, n), h);
    }

    /// <summary>
    /// The start in the span of the newest <paramref name="available"/> steps' dv (those with products): the
    /// coefficients c that satisfy the Galerkin conditions u_j . (b - sum_a c_a q_a) = 0, j, a &lt; m, into
    /// <see cref="_startCoefficients"/>, by Gaussian elimination with partial pivoting; when that m x m system is
    /// singular (steps whose dv are nearly dependent, as a cloth at rest gives) or its solution is not finite, the
    /// oldest step is dropped and the rest solved again. Returns m, or 0 when no step is left (the caller
    /// extrapolates).
    /// </summary>
    private int StartInSpan(ConjugateGradientPasses passes, int available)
    {
        var m = available;
        for (var a = 0; a < m; a++)
        {
            _startVectors[a] = _history.Dv(a);
            _startProducts[a] = _history.Product(a);
        }

        passes.WarmStartGram(_startVectors, _startProducts, m, _gram, _projections);
        var stride = m;
        for (; m > 0; m--)
        {
            if (SolveGalerkin(m, stride))
            {
                return m;
            }
        }

        return 0;
    }

    /// <summary>
    /// Solves the leading m x m block of the Gram matrix (row stride <paramref name="stride"/>) against the
    /// projections into <see cref="_startCoefficients"/>, by LU (<see cref="DenseLinearSolver.SolveLu"/>); false when
    /// a pivot is at most 1e-12 of the block's largest entry, when m = 1 and u . q is not positive (u . q ~ u . A u
    /// must be, A being positive definite, else the product is not to be trusted), or when a coefficient is not finite.
    /// </summary>
    private bool SolveGalerkin(int m, int stride)
    {
        var scale = 0.0;
        for (var i = 0; i < m; i++)
        {
            for (var j = 0; j < m; j++)
            {
                _elimination[(i * m) + j] = _gram[(i * stride) + j];
                scale = Math.Max(scale, Math.Abs(_gram[(i * stride) + j]));
            }

            _startCoefficients[i] = _projections[i];
        }

        if ((m == 1 && !(_elimination[0] > 0.0)) || !DenseLinearSolver.SolveLu(_elimination, _eliminationPivots, _startCoefficients, m, 1e-12 * scale))
        {
            return false;
        }

        for (var i = 0; i < m; i++)
        {
            if (!DoubleChecks.IsFinite(_startCoefficients[i]))
            {
                return false;
            }
        }

        return true;
    }

    /// <summary>
    /// z = P r with the multigrid, or block Jacobi (also when the multigrid is not positive along r: a force whose
    /// couplings are not of pair form); returns r . z, summed in chunk order.
    /// </summary>
    private double Precondition(ConjugateGradientPasses passes, ref bool multigrid)
    {
        if (multigrid)
        {
            passes.Restrict(_multigrid!);
            var rz = passes.CycleAndProlong(_multigrid!);
            if (rz > 0.0)
            {
                return rz;
            }

            multigrid = false;
        }

        return passes.Jacobi();
    }

    /// <summary>Throws the step's failure at the first value of <paramref name="values"/> (3 per particle) that is not finite, skipping pinned particles.</summary>
    private void CheckFinite(double[] values, Span<double> inverseMasses, double time, double end, string cause)
    {
        var bad = DoubleChecks.FirstNonFinite(values);
        while (bad >= 0 && inverseMasses[bad / 3] == 0.0)
        {
            var rest = DoubleChecks.FirstNonFinite(values.AsSpan(bad + 1));
            bad = rest < 0 ? -1 : bad + 1 + rest;
        }

        if (bad >= 0)
        {
            throw Diverged(time, end, bad, values[bad], string.Format(
                System.Globalization.CultureInfo.InvariantCulture, cause, bad / 3, values[bad]));
        }
    }

    /// <summary>The failure of a step at coordinate <paramref name="k"/> (its velocity component in the state vector).</summary>
    private SimulationDivergedException Diverged(double time, double end, int k, double value, string cause)
    {
        LastConverged = false;
        var n = _force?.Length ?? 0;
        return new SimulationDivergedException(end, time, n + k, k / 3, value, double.MaxValue, cause);
    }

    /// <summary>
    /// jw = J z, and z . w with w = (M - J) z on the free particles (0 on the pinned ones), summed in chunk order; fails
    /// the step when it is not finite. w itself is computed again from z and jw by the update that follows.
    /// </summary>
    private double ApplySystemMatrix(
        ILinearizableSystem system, IJacobianProductTail? tail, ConjugateGradientPasses passes, double time, double end)
    {
        // jw is 0 here: every pass that reads it last (the right-hand side, the residual, the update that takes
        // w = M z - jw) clears it as it goes, so no separate pass clears it before each product. (A solve that ends
        // on delta <= 0 right after this product leaves it J z; the next step clears it at its start.)
        AddProduct(system, tail, passes.Z, passes.JacobianProduct);
        var zw = passes.MassMinusJacobian();
        if (!DoubleChecks.IsFinite(zw))
        {
            throw Diverged(time, end, 0, zw, "the implicit system's matrix M - h D - h^2 K is not finite: the step is too large for these forces");
        }

        return zw;
    }

    /// <summary>
    /// jw += J w; with a uniform tail, only the terms before it (the pass that reads jw next adds the tail).
    /// </summary>
    private static void AddProduct(ILinearizableSystem system, IJacobianProductTail? tail, double[] w, double[] jw)
    {
        if (tail is not null)
        {
            tail.AddJacobianProductBeforeTail(w, jw);
        }
        else
        {
            system.AddJacobianProduct(w, jw);
        }
    }
}
