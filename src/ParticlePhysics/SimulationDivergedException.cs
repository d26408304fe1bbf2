using System;
using System.Globalization;
using ParticlePhysics.Numerics;

namespace ParticlePhysics;

/// <summary>
/// Thrown when a step produces a state that is not finite (NaN or infinite), or whose magnitude passes the
/// system's divergence limit. The system is left at its last good state and time, so the caller can retry with a
/// smaller time step or with <see cref="Integrators.ImplicitEuler"/> (<c>implicit-euler</c> in
/// <see cref="Integrators.IntegratorCatalog"/>), which stays stable at large steps on stiff springs.
/// </summary>
public sealed class SimulationDivergedException : Exception
{
    /// <summary>Creates the exception for a failed step.</summary>
    /// <param name="time">The time the failed step was to reach, in seconds.</param>
    /// <param name="lastFiniteTime">The time of the last finite state, where the system was left.</param>
    /// <param name="component">The index, in the state vector, of the first value that was not finite.</param>
    /// <param name="particle">The particle that value belongs to, or -1 for a system that has no particles.</param>
    /// <param name="value">The offending value (NaN, infinite, or beyond <paramref name="limit"/>).</param>
    /// <param name="limit">The divergence limit in force.</param>
    public SimulationDivergedException(
        double time, double lastFiniteTime, int component, int particle, double value, double limit)
        : base(BuildMessage(time, lastFiniteTime, component, particle, value, limit))
    {
        _cause = Cause(component, particle, value, limit);
        Time = time;
        LastFiniteTime = lastFiniteTime;
        Component = component;
        Particle = particle;
        Value = value;
        Limit = limit;
    }

    /// <summary>
    /// Creates the exception for a step that failed before it had a state to check: an integrator that met a value
    /// that is not finite on its way (a force, a right-hand side, a residual).
    /// </summary>
    /// <param name="time">The time the failed step was to reach, in seconds.</param>
    /// <param name="lastFiniteTime">The time of the last finite state, where the system was left.</param>
    /// <param name="component">The index, in the state vector, of the value the failure concerns.</param>
    /// <param name="particle">The particle that value belongs to, or -1.</param>
    /// <param name="value">The offending value.</param>
    /// <param name="limit">The divergence limit in force.</param>
    /// <param name="cause">What went wrong, as a clause: "the force on particle 3 is NaN".</param>
    public SimulationDivergedException(
        double time, double lastFiniteTime, int component, int particle, double value, double limit, string cause)
        : base(BuildMessage(time, lastFiniteTime, cause))
    {
        _cause = cause;
        Time = time;
        LastFiniteTime = lastFiniteTime;
        Component = component;
        Particle = particle;
        Value = value;
        Limit = limit;
    }

    private readonly string _cause;

    /// <summary>The time the failed step was to reach, in seconds.</summary>
    public double Time { get; }

    /// <summary>The time of the last finite state, at which the system was left.</summary>
    public double LastFiniteTime { get; }

    /// <summary>The index in the state vector of the first value that was not finite.</summary>
    public int Component { get; }

    /// <summary>The particle whose position or velocity stopped being finite, or -1 for a system without particles.</summary>
    public int Particle { get; }

    /// <summary>The offending value: NaN, infinite, or finite but beyond the divergence limit.</summary>
    public double Value { get; }

    /// <summary>The divergence limit in force (<see cref="ParticleWorld.DivergenceLimit"/>).</summary>
    public double Limit { get; }

    /// <summary>The same failure, reported by a caller that rolled the system back further, to <paramref name="lastFiniteTime"/>.</summary>
    internal SimulationDivergedException RewoundTo(double lastFiniteTime) =>
        new(Time, lastFiniteTime, Component, Particle, Value, Limit, _cause);

    private static string BuildMessage(
        double time, double lastFiniteTime, int component, int particle, double value, double limit) =>
        BuildMessage(time, lastFiniteTime, Cause(component, particle, value, limit));

    private static string Cause(int component, int particle, double value, double limit)
    {
        var what = particle >= 0
            ? string.Format(CultureInfo.InvariantCulture, "particle {0}", particle)
            : string.Format(CultureInfo.InvariantCulture, "state component {0}", component);
        var how = DoubleChecks.IsFinite(value)
            ? string.Format(CultureInfo.InvariantCulture, "reached {0:R}, beyond the divergence limit {1:R}", value, limit)
            : string.Format(CultureInfo.InvariantCulture, "is no longer finite ({0})", value);
        return what + " " + how;
    }

    private static string BuildMessage(double time, double lastFiniteTime, string cause) =>
        string.Format(
            CultureInfo.InvariantCulture,
            "The simulation diverged at t={0:R}: {1}. The system was left at its last good state, t={2:R}; "
            + "retry with a smaller time step, or with ImplicitEuler (implicit-euler), which stays stable at large steps.",
            time,
            cause,
            lastFiniteTime);
}
