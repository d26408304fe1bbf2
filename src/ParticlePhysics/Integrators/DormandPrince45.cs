using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Integrators;

/// <summary>
/// Adaptive Runge-Kutta of order 5 with an embedded order-4 error estimate (Dormand-Prince 5(4)). One call to
/// <see cref="Step"/> integrates exactly from t to t + dt with as many internal steps as the tolerance needs,
/// rejecting and retrying steps whose error estimate is too large: dt is the output interval.
/// </summary>
/// <remarks>
/// Seven stages k1..k7 with the Dormand-Prince tableau; y5 = y + h sum b_i k_i is kept, and the error estimate
/// e = h sum (b_i - b*_i) k_i compares it with the embedded fourth-order solution. The scaled error
/// err = max_i |e_i| / (tol (1 + max(|y_i|, |y5_i|))) must be at most 1 for a step to be accepted (a bound on
/// every component, not an average that zero components would dilute); the
/// next step size is h * clamp(0.9 err^(-1/5), 0.2, 5). The last stage is evaluated at the new state and is the
/// next step's first (FSAL). Internal steps are shortened so that the interval ends exactly at t + dt.
/// Stability: adaptive, so it follows the fastest time scale of the system; on a stiff cloth it takes many
/// small steps rather than diverging. Use <c>implicit-euler</c> for stiff systems at large steps.
/// Bounded work: the tolerance is at least <see cref="MinTolerance"/> (100 machine epsilons, the floor of MATLAB's
/// ode45 and SciPy's solve_ivp: below it the error estimate is rounding noise and no step passes); a call takes at most
/// <see cref="MaxStepsPerCall"/> internal steps; and an internal step that must shrink below 16 units in the last
/// place of t fails the call. Each failure throws <see cref="SolverNotConvergedException"/> before anything is
/// committed.
/// </remarks>
public sealed class DormandPrince45 : IStatefulIntegrator
{
    private const double Safety = 0.9;
    private const double MinFactor = 0.2;
    private const double MaxFactor = 5.0;

    // Tableau (Dormand & Prince 1980).
    private const double C2 = 1.0 / 5, C3 = 3.0 / 10, C4 = 4.0 / 5, C5 = 8.0 / 9;
    private const double A21 = 1.0 / 5;
    private const double A31 = 3.0 / 40, A32 = 9.0 / 40;
    private const double A41 = 44.0 / 45, A42 = -56.0 / 15, A43 = 32.0 / 9;
    private const double A51 = 19372.0 / 6561, A52 = -25360.0 / 2187, A53 = 64448.0 / 6561, A54 = -212.0 / 729;
    private const double A61 = 9017.0 / 3168, A62 = -355.0 / 33, A63 = 46732.0 / 5247, A64 = 49.0 / 176;
    private const double A65 = -5103.0 / 18656;
    private const double B1 = 35.0 / 384, B3 = 500.0 / 1113, B4 = 125.0 / 192, B5 = -2187.0 / 6784, B6 = 11.0 / 84;

    // Error coefficients b - b*, where b* is the embedded fourth-order solution.
    private const double E1 = 71.0 / 57600, E3 = -71.0 / 16695, E4 = 71.0 / 1920, E5 = -17253.0 / 339200;
    private const double E6 = 22.0 / 525, E7 = -1.0 / 40;

    private readonly double[][] _k = new double[7][];
    private double[]? _y;
    private double[]? _stage;
    private double _tolerance;
    private double _stepSize;
    private double _pendingStepSize = -1; // the step size the last Step ended with, until committed; -1: none
    private int _maxStepsPerCall = DefaultMaxStepsPerCall;

    /// <summary>Creates the integrator.</summary>
    /// <param name="tolerance">The error bound per internal step, relative to 1 + |y| for each component.</param>
    public DormandPrince45(double tolerance = 1e-8)
    {
        Tolerance = tolerance;
    }

    /// <inheritdoc />
    public string Name => "rk45";

    /// <inheritdoc />
    public int Order => 5;

    /// <summary>The smallest <see cref="Tolerance"/>: 100 machine epsilons, 2.2e-14.</summary>
    public const double MinTolerance = 100 * 2.220446049250313e-16;

    /// <summary>The default <see cref="MaxStepsPerCall"/>: 10,000 internal steps (about 70,000 evaluations).</summary>
    public const int DefaultMaxStepsPerCall = 10_000;

    /// <summary>The error bound per internal step: a finite number from <see cref="MinTolerance"/> up (default 1e-8).</summary>
    public double Tolerance
    {
        get => _tolerance;
        set
        {
            Guard.PositiveFinite(value, nameof(Tolerance));
            if (value < MinTolerance)
            {
                throw new ArgumentOutOfRangeException(
                    nameof(Tolerance),
                    value,
                    $"Tolerance must be at least {Guard.Format(MinTolerance)} (100 machine epsilons: below it the error "
                    + $"estimate is rounding noise and no step can pass); got {Guard.Format(value)}.");
            }

            _tolerance = value;
        }
    }

    /// <summary>
    /// The most internal steps (accepted or rejected) one call to <see cref="Step"/> may take, at least 1 (default
    /// <see cref="DefaultMaxStepsPerCall"/>); a call that needs more throws <see cref="SolverNotConvergedException"/>.
    /// </summary>
    public int MaxStepsPerCall
    {
        get => _maxStepsPerCall;
        set
        {
            if (value < 1)
            {
                throw new ArgumentOutOfRangeException(
                    nameof(MaxStepsPerCall), value, $"MaxStepsPerCall must be at least 1; got {value}.");
            }

            _maxStepsPerCall = value;
        }
    }

    /// <summary>The internal step size that the next call starts from, or 0 before the first call.</summary>
    public double CurrentStepSize
    {
        get => _stepSize;
        set
        {
            Guard.NonNegativeFinite(value, nameof(CurrentStepSize));
            _stepSize = value;
            _pendingStepSize = -1;
        }
    }

    /// <summary>Internal steps accepted since the integrator was created.</summary>
    public long AcceptedSteps { get; private set; }

    /// <summary>Internal steps rejected (and retried smaller) since the integrator was created.</summary>
    public long RejectedSteps { get; private set; }

    /// <summary>Evaluations of the system since the integrator was created.</summary>
    public long Evaluations { get; private set; }

    /// <inheritdoc />
    /// <exception cref="SolverNotConvergedException">
    /// The interval needs more than <see cref="MaxStepsPerCall"/> internal steps, or an internal step below the
    /// smallest step size, to meet <see cref="Tolerance"/>; the state and the step size are left as they were.
    /// </exception>
    public void Step(IOdeSystem system, double time, ReadOnlySpan<double> state, Span<double> next, double dt)
    {
        StepChecks.Check(system, state, next, dt);
        _pendingStepSize = -1;
        var n = state.Length;
        for (var s = 0; s < _k.Length; s++)
        {
            _k[s] = StepChecks.Sized(_k[s], n);
        }

        var y = _y = StepChecks.Sized(_y, n);
        var stage = _stage = StepChecks.Sized(_stage, n);
        state.CopyTo(y);
        var end = time + dt;
        var t = time;
        Evaluate(system, t, y, _k[0]);
        var h = _stepSize > 0 ? _stepSize : InitialStepSize(system, t, y, _k[0], stage, _k[1]);
        var attempts = 0;

        while (t < end)
        {
            if (attempts++ == _maxStepsPerCall)
            {
                throw new SolverNotConvergedException(end, attempts - 1, double.NaN, _tolerance, string.Format(
                    System.Globalization.CultureInfo.InvariantCulture,
                    "rk45 needed more than {0} internal steps for the interval from t={1:R} to t={2:R} (it reached t={3:R} "
                    + "with steps of {4:R} s). Take a shorter dt (the output interval), raise MaxStepsPerCall or "
                    + "loosen Tolerance, or use implicit-euler for a stiff system.",
                    _maxStepsPerCall,
                    time,
                    end,
                    t,
                    h));
            }

            // The smallest step worth taking at t: 16 units in the last place of t (of the time reached, not of the
            // interval's end, which for a long interval would pass every step however bad its error).
            var minimum = 16 * Ulp(Math.Abs(t));
            var last = t + h >= end;
            var attempt = last ? end - t : h;
            var error = Attempt(system, t, y, attempt, next);
            if (error > 1.0 && attempt <= minimum)
            {
                if (DoubleChecks.FirstNonFinite(next) >= 0)
                {
                    // The derivative is not finite at any step size: leave the result to the caller's finiteness
                    // check, which reports it as a divergence (as for every other integrator).
                    return;
                }

                throw new SolverNotConvergedException(end, attempts, error, _tolerance, string.Format(
                    System.Globalization.CultureInfo.InvariantCulture,
                    "rk45 could not meet its tolerance {0:R} at t={1:R}: the step shrank to {2:R} s, the smallest it can "
                    + "take there, with a scaled error of {3:R}. Loosen Tolerance, or use implicit-euler for a stiff system.",
                    _tolerance,
                    t,
                    attempt,
                    error));
            }

            if (error <= 1.0)
            {
                AcceptedSteps++;
                t = last ? end : t + attempt;
                next.CopyTo(y);
                (_k[0], _k[6]) = (_k[6], _k[0]);
                var grow = error == 0.0 ? MaxFactor : Math.Min(MaxFactor, Math.Max(MinFactor, Safety * Math.Pow(error, -0.2)));
                if (!last || attempt >= h)
                {
                    h = attempt * grow;
                }

                if (DoubleChecks.FirstNonFinite(y) >= 0)
                {
                    break;
                }
            }
            else
            {
                RejectedSteps++;
                var shrink = DoubleChecks.IsFinite(error) ? Math.Max(MinFactor, Safety * Math.Pow(error, -0.2)) : MinFactor;
                h = Math.Max(attempt * Math.Min(1.0, shrink), minimum);
            }
        }

        _pendingStepSize = h;
        y.AsSpan().CopyTo(next);
    }

    /// <inheritdoc />
    /// <remarks>The step size the last call ended with becomes the one the next call starts from.</remarks>
    public void CommitStep()
    {
        if (_pendingStepSize >= 0)
        {
            _stepSize = _pendingStepSize;
            _pendingStepSize = -1;
        }
    }

    /// <inheritdoc />
    public void DiscardStep() => _pendingStepSize = -1;

    /// <inheritdoc />
    /// <remarks>One value: <see cref="CurrentStepSize"/>, the internal step the next call starts from.</remarks>
    public int StateLength => 1;

    /// <inheritdoc />
    public void WriteState(Span<double> destination)
    {
        if (destination.Length != StateLength)
        {
            throw new ArgumentException(
                $"destination must hold exactly {StateLength} value; it holds {destination.Length}.", nameof(destination));
        }

        destination[0] = _stepSize;
    }

    /// <inheritdoc />
    public void ReadState(ReadOnlySpan<double> source)
    {
        if (source.Length != StateLength)
        {
            throw new ArgumentException(
                $"source must hold exactly {StateLength} value; it holds {source.Length}.", nameof(source));
        }

        CurrentStepSize = source.ForReading()[0]; // checks the value, and forgets a step not committed
    }

    private static double Ulp(double x) => Math.Max(double.Epsilon, x * 2.220446049250313e-16);

    private void Evaluate(IOdeSystem system, double t, ReadOnlySpan<double> y, Span<double> dydt)
    {
        Evaluations++;
        system.Evaluate(t, y, dydt);
    }

    /// <summary>One Dormand-Prince step of size h from (t, y) with k1 = _k[0] known; writes y5 into result, returns err.</summary>
    private double Attempt(IOdeSystem system, double t, double[] y, double h, Span<double> result)
    {
        var n = y.Length;
        double[] k1 = _k[0], k2 = _k[1], k3 = _k[2], k4 = _k[3], k5 = _k[4], k6 = _k[5], k7 = _k[6];
        var s = _stage!;
        for (var i = 0; i < n; i++)
        {
            s[i] = y[i] + (h * A21 * k1[i]);
        }

        Evaluate(system, t + (C2 * h), s, k2);
        for (var i = 0; i < n; i++)
        {
            s[i] = y[i] + (h * ((A31 * k1[i]) + (A32 * k2[i])));
        }

        Evaluate(system, t + (C3 * h), s, k3);
        for (var i = 0; i < n; i++)
        {
            s[i] = y[i] + (h * ((A41 * k1[i]) + (A42 * k2[i]) + (A43 * k3[i])));
        }

        Evaluate(system, t + (C4 * h), s, k4);
        for (var i = 0; i < n; i++)
        {
            s[i] = y[i] + (h * ((A51 * k1[i]) + (A52 * k2[i]) + (A53 * k3[i]) + (A54 * k4[i])));
        }

        Evaluate(system, t + (C5 * h), s, k5);
        for (var i = 0; i < n; i++)
        {
            s[i] = y[i] + (h * ((A61 * k1[i]) + (A62 * k2[i]) + (A63 * k3[i]) + (A64 * k4[i]) + (A65 * k5[i])));
        }

        Evaluate(system, t + h, s, k6);
        for (var i = 0; i < n; i++)
        {
            result[i] = y[i] + (h * ((B1 * k1[i]) + (B3 * k3[i]) + (B4 * k4[i]) + (B5 * k5[i]) + (B6 * k6[i])));
        }

        Evaluate(system, t + h, result, k7);
        var error = 0.0;
        for (var i = 0; i < n; i++)
        {
            var e = h * ((E1 * k1[i]) + (E3 * k3[i]) + (E4 * k4[i]) + (E5 * k5[i]) + (E6 * k6[i]) + (E7 * k7[i]));
            var scale = _tolerance * (1.0 + Math.Max(Math.Abs(y[i]), Math.Abs(result[i])));
            var r = Math.Abs(e) / scale;
            error = r > error || !DoubleChecks.IsFinite(r) ? r : error;
        }

        return DoubleChecks.IsFinite(error) ? error : double.PositiveInfinity;
    }

    /// <summary>Hairer, Norsett and Wanner's starting step: one extra evaluation, scaled by the tolerance.</summary>
    private double InitialStepSize(IOdeSystem system, double t, double[] y, double[] f0, double[] stage, double[] f1)
    {
        var n = y.Length;
        double d0 = 0, d1 = 0;
        for (var i = 0; i < n; i++)
        {
            var scale = _tolerance * (1.0 + Math.Abs(y[i]));
            d0 += (y[i] / scale) * (y[i] / scale);
            d1 += (f0[i] / scale) * (f0[i] / scale);
        }

        d0 = Math.Sqrt(d0 / n);
        d1 = Math.Sqrt(d1 / n);
        var h0 = d0 < 1e-5 || d1 < 1e-5 ? 1e-6 : 0.01 * d0 / d1;
        for (var i = 0; i < n; i++)
        {
            stage[i] = y[i] + (h0 * f0[i]);
        }

        Evaluate(system, t + h0, stage, f1);
        double d2 = 0;
        for (var i = 0; i < n; i++)
        {
            var scale = _tolerance * (1.0 + Math.Abs(y[i]));
            var r = (f1[i] - f0[i]) / scale;
            d2 += r * r;
        }

        d2 = Math.Sqrt(d2 / n) / h0;
        var largest = Math.Max(d1, d2);
        var h1 = largest <= 1e-15 ? Math.Max(1e-6, h0 * 1e-3) : Math.Pow(0.01 / largest, 0.2);
        var h = Math.Min(100 * h0, h1);
        return DoubleChecks.IsFinite(h) && h > 0 ? h : 1e-6;
    }
}
