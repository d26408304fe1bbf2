using System;
using System.Collections.Generic;

namespace ParticlePhysics.Integrators;

/// <summary>
/// The integrators by the names the demo's <c>--integrator</c> option and configuration files use.
/// </summary>
public static class IntegratorCatalog
{
    /// <summary>The default integrator's name.</summary>
    public const string DefaultName = "rk4";

    private static readonly string[] _names =
    {
        "explicit-euler", "semi-implicit-euler", "implicit-euler", "rk4", "velocity-verlet", "rk45", "xpbd",
    };

    /// <summary>The names that <see cref="Create"/> accepts.</summary>
    public static IReadOnlyList<string> Names => _names;

    /// <summary>
    /// True for the integrators that need a position/velocity system (<see cref="ISecondOrderSystem"/>; xpbd needs an
    /// <see cref="IPositionBasedSystem"/>, which is one).
    /// </summary>
    public static bool NeedsSecondOrderSystem(string name) =>
        name is "semi-implicit-euler" or "velocity-verlet" or "xpbd";

    /// <summary>True for the position-based integrators (<c>xpbd</c>), which need an <see cref="IPositionBasedSystem"/>.</summary>
    public static bool IsPositionBased(string name) => name == "xpbd";

    /// <summary>
    /// True for the adaptive integrators (<c>rk45</c>), whose error follows their tolerance rather than the step
    /// they are given, which is then only the output interval.
    /// </summary>
    public static bool IsAdaptive(string name) => name == "rk45";

    /// <summary>True when the integrator <paramref name="name"/> can advance <paramref name="system"/>.</summary>
    public static bool AppliesTo(string name, IOdeSystem system)
    {
        Guard.NotNull(system, nameof(system));
        return Array.IndexOf(_names, name) >= 0
            && (system is ISecondOrderSystem || !NeedsSecondOrderSystem(name))
            && (system is IPositionBasedSystem || !IsPositionBased(name));
    }

    /// <summary>Creates a new integrator (each owns its scratch buffers, so use one per system).</summary>
    /// <param name="name">One of <see cref="Names"/>.</param>
    /// <param name="tolerance">The error bound per step for <c>rk45</c>; ignored by the fixed-step integrators.</param>
    /// <param name="substeps">The substeps per step of <c>xpbd</c> (1 to 1000, default 10); ignored by the others.</param>
    public static IIntegrator Create(string name, double tolerance = 1e-8, int substeps = Xpbd.DefaultSubsteps) => name switch
    {
        "explicit-euler" => new ExplicitEuler(),
        "semi-implicit-euler" => new SemiImplicitEuler(),
        "implicit-euler" => new ImplicitEuler(),
        "rk4" => new RungeKutta4(),
        "velocity-verlet" => new VelocityVerlet(),
        "rk45" => new DormandPrince45(tolerance),
        "xpbd" => new Xpbd(substeps),
        _ => throw new ArgumentException(
            $"Unknown integrator '{name}'; expected one of: {string.Join(", ", _names)}.", nameof(name)),
    };
}
