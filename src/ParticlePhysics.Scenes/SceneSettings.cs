using ParticlePhysics.Aerodynamics;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Scenes;

/// <summary>
/// The top-level settings of a scene file: gravity, drag, the integrator, the step, the duration and particle
/// collisions, with the contract's defaults (<see cref="Scene"/> reads and checks them).
/// </summary>
public sealed class SceneSettings
{
    /// <summary>The default step, 1/60 s.</summary>
    public const double DefaultTimeStep = 1.0 / 60.0;

    /// <summary>The default duration, 5 s.</summary>
    public const double DefaultDuration = 5;

    /// <summary>The default integrator, <c>xpbd</c>.</summary>
    public const string DefaultIntegrator = "xpbd";

    /// <summary>[gx, gy, gz] in m/s^2 (default [0, -9.81, 0]): the force m g on every particle.</summary>
    public Vector3d Gravity { get; internal set; } = new(0, -Forces.Gravity.StandardAcceleration, 0);

    /// <summary>Linear drag lambda on every particle, N s/m (F = -lambda v; default 0).</summary>
    public double Drag { get; internal set; }

    /// <summary>The speed below which what stays still falls asleep (<see cref="ParticleWorld.SleepSpeed"/>), m/s; 0 (the default): never.</summary>
    public double SleepSpeed { get; internal set; }

    /// <summary>How long it must stay below <see cref="SleepSpeed"/>, s (default 0.5).</summary>
    public double SleepTime { get; internal set; } = ParticleWorld.DefaultSleepTime;

    /// <summary>The integrator's name in <see cref="IntegratorCatalog"/> (default xpbd).</summary>
    public string Integrator { get; internal set; } = DefaultIntegrator;

    /// <summary>xpbd's substeps per step (default 10).</summary>
    public int Substeps { get; internal set; } = Xpbd.DefaultSubsteps;

    /// <summary>rk45's error bound per step (default 1e-8).</summary>
    public double Tolerance { get; internal set; } = 1e-8;

    /// <summary>The step dt, s (default 1/60; for rk45 the output interval).</summary>
    public double TimeStep { get; internal set; } = DefaultTimeStep;

    /// <summary>The simulated time, s (default 5).</summary>
    public double Duration { get; internal set; } = DefaultDuration;

    /// <summary>True when every particle with a radius collides with every other (pairs joined by a spring or a link excepted).</summary>
    public bool ParticleCollisions { get; internal set; }

    /// <summary>The restitution of particle-particle impacts, 0 to 1 (default 0).</summary>
    public double ParticleRestitution { get; internal set; }

    /// <summary>The Coulomb friction between particles (default 0).</summary>
    public double ParticleFriction { get; internal set; }

    /// <summary>
    /// The air of the file's <c>air</c> (null when it has none): what the cloths with <c>aerodynamics</c> move in. Each
    /// world built from the scene gets a copy of its own, so that changing one world's wind leaves the others alone.
    /// </summary>
    public Air? Air { get; internal set; }

    /// <summary>The air the cloths with <c>aerodynamics</c> move in: a copy of <see cref="Air"/>, or the contract's default still air.</summary>
    internal Air NewAir() => Air is { } air
        ? new Air(air.Density, air.Velocity, air.DragCoefficient, air.LiftCoefficient) { Gust = air.Gust }
        : new Air(Aerodynamics.Air.StandardDensity, Vector3d.Zero, 1.0, 0.0);
}
