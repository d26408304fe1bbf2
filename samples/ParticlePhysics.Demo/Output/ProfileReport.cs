using System.Globalization;
using System.IO;
using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Demo.Output;

/// <summary>
/// What <c>--profile</c> prints after a run, on standard error (so that csv and json stay machine-readable): each
/// stage's total wall-clock time, its mean per step and its share of the step, then the counts per step.
/// </summary>
internal static class ProfileReport
{
    public static void Write(TextWriter output, StageTimings timings)
    {
        var total = timings.Total;
        var steps = timings.Steps;
        if (steps == 0)
        {
            output.WriteLine("profile: no step was committed, so there is nothing to show.");
            return;
        }

        output.WriteLine($"profile of {steps} {(steps == 1 ? "step" : "steps")} (wall clock; the stages do not overlap, integration is the rest of the step):");
        var table = new TextTable("stage", ">total (ms)", ">per step (us)", ">share");
        void Row(string name, double seconds) => table.Add(
            name,
            Fixed(seconds * 1e3, 3),
            Fixed(seconds * 1e6 / steps, 2),
            total.TotalSeconds > 0 ? Fixed(100 * seconds / total.TotalSeconds, 1) + " %" : "n/a");
        Row("integration", total.IntegrationSeconds);
        Row("forces", total.ForceSeconds);
        Row("constraints", total.ConstraintSeconds);
        Row("contacts", total.ContactSeconds);
        Row("  broad phase", total.BroadPhaseSeconds);
        Row("step", total.TotalSeconds);
        table.Write(output);
        output.WriteLine(
            $"per step: force evaluations {PerStep(total.ForceEvaluations, steps)}, Jacobian products {PerStep(total.JacobianProducts, steps)}, "
            + $"substeps {PerStep(total.Substeps, steps)}, constraint-set calls {PerStep(total.ConstraintCalls, steps)}, "
            + $"contact-set calls {PerStep(total.ContactCalls, steps)}, contact pairs {PerStep(total.ContactPairs, steps)}, contacts {PerStep(total.Contacts, steps)}");
    }

    private static string Fixed(double value, int decimals) => value.ToString("F" + decimals, CultureInfo.InvariantCulture);

    // A mean per step: whole when every step made the same number of calls, else two decimals.
    private static string PerStep(long count, int steps) =>
        count % steps == 0 ? (count / steps).ToString(CultureInfo.InvariantCulture) : Fixed((double)count / steps, 2);
}
