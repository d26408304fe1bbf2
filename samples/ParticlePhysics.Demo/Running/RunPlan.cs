using System;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Demo.Running;

/// <summary>
/// How a run is stepped: the integrator, the step, how many steps, which of them make rows (and xpbd's substeps), and
/// whether each step's stages are timed (<c>--profile</c>).
/// </summary>
internal sealed record RunPlan(string Integrator, double Dt, int Steps, int Every, double Tolerance, int Substeps = Xpbd.DefaultSubsteps, bool Profile = false)
{
    /// <summary>The number of rows the default <c>--every</c> aims at.</summary>
    public const int TargetRows = 200;

    /// <summary>The end time, Steps * Dt.</summary>
    public double EndTime => Steps * Dt;

    /// <summary>
    /// The number of steps of <paramref name="dt"/> that cover <paramref name="duration"/>: duration / dt when that is a
    /// whole number (to 1e-9), else the next whole number, so the run never stops short. Every step has the same dt.
    /// </summary>
    public static int StepsFor(double duration, double dt)
    {
        var ratio = duration / dt;
        var whole = Math.Round(ratio);
        var steps = Math.Abs(ratio - whole) <= 1e-9 * Math.Max(1.0, ratio) ? whole : Math.Ceiling(ratio);
        if (steps > int.MaxValue)
        {
            throw new UsageException(FormattableString.Invariant(
                $"--duration {duration} / --dt {dt} makes {steps:R} steps; at most {int.MaxValue} are allowed."));
        }

        return Math.Max(1, (int)steps);
    }

    /// <summary>The default <c>--every</c>: keeps the output near <see cref="TargetRows"/> rows.</summary>
    public static int DefaultEvery(int steps) => Math.Max(1, (int)Math.Ceiling(steps / (double)TargetRows));

    /// <summary>True for the steps that make a row: step 0, every N-th step, and the last one.</summary>
    public bool IsOutputStep(int step) => step % Every == 0 || step == Steps;
}
