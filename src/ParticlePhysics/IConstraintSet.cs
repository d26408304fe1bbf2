namespace ParticlePhysics;

/// <summary>
/// Constraints that the world enforces beyond forces (rods, cables, attachments, contacts with colliders and between
/// particles), in a stage of the step of their own: integrators never see them, and they never see integrators.
/// </summary>
/// <remarks>
/// <para>
/// After a force-based integrator (explicit, semi-implicit and implicit Euler, RK4, velocity Verlet, RK45) has
/// advanced the state over a step, the world calls <see cref="Resolve"/> on every set, in the order they were added,
/// with the start and the end of the step: a set moves the end positions and changes the end velocities (projection
/// onto a constraint, impulses), and may look at the path from the start to the end (a time of impact).
/// </para>
/// <para>
/// The position-based integrator (xpbd) enforces the same sets inside its substeps instead, through
/// <see cref="Project"/> (once per substep, after the prediction) and <see cref="SolveVelocities"/> (once per substep,
/// after the velocities are taken from the change of positions), so one constraint or collider is written once for
/// both kinds of integrator.
/// </para>
/// <para>A set must not allocate per call, must only move particles whose inverse mass is not 0, and must be
/// deterministic: the same context gives the same bits.</para>
/// </remarks>
public interface IConstraintSet
{
    /// <summary>Corrects the end of a force-based integrator's step (<see cref="ConstraintContext.Dt"/> is the step).</summary>
    void Resolve(in ConstraintContext context);

    /// <summary>Projects the positions once in a position-based substep (<see cref="ConstraintContext.Dt"/> is the substep).</summary>
    void Project(in ConstraintContext context);

    /// <summary>Corrects the velocities once in a position-based substep, after the positions (restitution, friction).</summary>
    void SolveVelocities(in ConstraintContext context);
}
