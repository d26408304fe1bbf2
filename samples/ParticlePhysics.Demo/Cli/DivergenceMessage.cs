using ParticlePhysics.Demo.Output;
using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Demo.Cli;

/// <summary>The one-line report of a diverged run, with what to try next.</summary>
internal static class DivergenceMessage
{
    public static string For(Divergence divergence, RunPlan plan)
    {
        var kept = $"the rows already printed were kept (last good state: t={Numbers.Brief((divergence.Step - 1) * plan.Dt)} s)";
        if (divergence.Exception is not SimulationDivergedException e)
        {
            // rk45 at a bound of its work: the core's message says which bound and what to change.
            return $"error: simulation stopped at t={Numbers.RoundTrip(divergence.Time)} s ({plan.Integrator}, dt = {Numbers.RoundTrip(plan.Dt)} s): "
                + $"{divergence.Exception.Message.TrimEnd('.')}; {kept}.";
        }

        // A particle world bounds speeds (ParticleWorld.DivergenceLimit, m/s) and only asks positions to be finite; a
        // plain ODE bounds every component.
        var who = e.Particle >= 0 ? $"particle {e.Particle}" : $"state component {e.Component}";
        var what = double.IsFinite(e.Value)
            ? e.Particle >= 0
                ? $"reached v{"xyz"[e.Component % 3]} = {Numbers.Brief(e.Value)} m/s, beyond the divergence limit {Numbers.Brief(e.Limit)} m/s"
                : $"reached {Numbers.Brief(e.Value)}, beyond the divergence limit {Numbers.Brief(e.Limit)}"
            : $"became {Numbers.RoundTrip(e.Value)}";
        var alternative = plan.Integrator == "implicit-euler" ? string.Empty : ", or --integrator implicit-euler";
        return $"error: simulation diverged at t={Numbers.RoundTrip(divergence.Time)} s ({plan.Integrator}, dt = {Numbers.RoundTrip(plan.Dt)} s: {who} {what}); "
            + $"{kept}. Try a smaller --dt, such as {Numbers.RoundTrip(plan.Dt / 4)}{alternative}.";
    }
}
