namespace ParticlePhysics;

/// <summary>How <see cref="Integrators.ImplicitEuler"/> treats a force generator that does not implement <see cref="IForceJacobian"/>.</summary>
public enum UserForceTreatment
{
    /// <summary>
    /// The force enters the step at its value at the start of the step, like explicit Euler (the default): cheap and
    /// safe for gentle forces such as wind, but a stiff force of your own then limits the stable time step.
    /// </summary>
    Explicit,

    /// <summary>
    /// The force is linearised too, by finite-difference Jacobian-vector products (one extra evaluation of that
    /// generator per conjugate-gradient iteration). Use it for stiff forces; the force's Jacobian should be
    /// symmetric, as the solver assumes.
    /// </summary>
    FiniteDifference,
}
