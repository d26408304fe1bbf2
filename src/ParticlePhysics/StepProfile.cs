using System;

namespace ParticlePhysics;

/// <summary>
/// What one step of a <see cref="ParticleWorld"/> cost, stage by stage: <see cref="ParticleWorld.LastStepProfile"/>
/// after a step taken with <see cref="ParticleWorld.Profiling"/> on. Times are wall-clock seconds between
/// <see cref="System.Diagnostics.Stopwatch"/> timestamps the world takes around what it calls (a few per evaluation and
/// per constraint set, never per particle); counts are the calls it made. The stages do not overlap, and
/// <see cref="IntegrationSeconds"/> is the rest of the step, so the four stages add up to <see cref="TotalSeconds"/>.
/// </summary>
/// <remarks>
/// <para>
/// The stages, after Box2D's <c>b2Profile</c> and Jitter2's per-phase timings:
/// <list type="bullet">
/// <item><see cref="ForceSeconds"/>: the force generators in every evaluation, and under implicit Euler the forces'
/// linearisation, Jacobian products and diagonal blocks.</item>
/// <item><see cref="ConstraintSeconds"/>: the constraint sets that are not contacts (rods, cables, spring projections,
/// your own): their <see cref="IConstraintSet.Resolve"/>, <see cref="IConstraintSet.Project"/> and
/// <see cref="IConstraintSet.SolveVelocities"/>, and the constraint forces they add in each evaluation
/// (<see cref="IConstraintForces"/>).</item>
/// <item><see cref="ContactSeconds"/>: the contact sets' calls, their broad phase included
/// (<see cref="BroadPhaseSeconds"/> is the part they report spending there).</item>
/// <item><see cref="IntegrationSeconds"/>: everything else in the step: the integrator's own arithmetic (prediction,
/// stages, the implicit solver's vectors and preconditioner), the divergence check and the commit.</item>
/// </list>
/// </para>
/// <para>
/// Profiling changes no result: the timestamps are read, never used by the step. A profile is all or nothing like the
/// step: a step that fails leaves <see cref="ParticleWorld.LastStepProfile"/> at the last committed step's.
/// </para>
/// </remarks>
public readonly struct StepProfile : IEquatable<StepProfile>
{
    /// <summary>A profile of the given stage times (in seconds) and counts.</summary>
    internal StepProfile(
        double totalSeconds,
        double forceSeconds,
        double constraintSeconds,
        double contactSeconds,
        double broadPhaseSeconds,
        int forceEvaluations,
        int jacobianProducts,
        int substeps,
        int constraintCalls,
        int contactCalls,
        int contactPairs,
        int contacts)
    {
        TotalSeconds = totalSeconds;
        ForceSeconds = forceSeconds;
        ConstraintSeconds = constraintSeconds;
        ContactSeconds = contactSeconds;
        BroadPhaseSeconds = broadPhaseSeconds;
        ForceEvaluations = forceEvaluations;
        JacobianProducts = jacobianProducts;
        Substeps = substeps;
        ConstraintCalls = constraintCalls;
        ContactCalls = contactCalls;
        ContactPairs = contactPairs;
        Contacts = contacts;
    }

    /// <summary>The whole step, in seconds, from its start to its commit.</summary>
    public double TotalSeconds { get; }

    /// <summary>
    /// The integrator's own work and the commit, in seconds: <see cref="TotalSeconds"/> minus the other three stages
    /// (0 if a force or a set called back into the world's evaluation, so that a time was counted twice).
    /// </summary>
    public double IntegrationSeconds => Math.Max(0.0, TotalSeconds - ForceSeconds - ConstraintSeconds - ContactSeconds);

    /// <summary>The force generators, and under implicit Euler their linearisation and products, in seconds.</summary>
    public double ForceSeconds { get; }

    /// <summary>The constraint sets other than contacts, and the constraint forces they add, in seconds.</summary>
    public double ConstraintSeconds { get; }

    /// <summary>The contact sets, broad phase included, in seconds.</summary>
    public double ContactSeconds { get; }

    /// <summary>The part of <see cref="ContactSeconds"/> the contact sets report spending in their broad phase.</summary>
    public double BroadPhaseSeconds { get; }

    /// <summary>
    /// How many times the forces were evaluated (rk4: 4 per step; xpbd: one per substep; implicit Euler: one, with its
    /// linearisation).
    /// </summary>
    public int ForceEvaluations { get; }

    /// <summary>Products with the forces' Jacobian: about one per iteration of implicit Euler's solver; 0 otherwise.</summary>
    public int JacobianProducts { get; }

    /// <summary>Position-based substeps (xpbd: each projects every constraint set once); 0 under the force-based integrators.</summary>
    public int Substeps { get; }

    /// <summary>Calls to the constraint sets other than contacts (Resolve, Project, SolveVelocities, constraint forces).</summary>
    public int ConstraintCalls { get; }

    /// <summary>Calls to the contact sets.</summary>
    public int ContactCalls { get; }

    /// <summary>The candidate pairs the contact sets' broad phase listed, over all their calls.</summary>
    public int ContactPairs { get; }

    /// <summary>The contacts the contact sets resolved, over all their calls.</summary>
    public int Contacts { get; }

    /// <summary>
    /// The cost of two steps together (a frame of several steps, or a run): times and counts added.
    /// </summary>
    public static StepProfile operator +(StepProfile a, StepProfile b) => new(
        a.TotalSeconds + b.TotalSeconds,
        a.ForceSeconds + b.ForceSeconds,
        a.ConstraintSeconds + b.ConstraintSeconds,
        a.ContactSeconds + b.ContactSeconds,
        a.BroadPhaseSeconds + b.BroadPhaseSeconds,
        a.ForceEvaluations + b.ForceEvaluations,
        a.JacobianProducts + b.JacobianProducts,
        a.Substeps + b.Substeps,
        a.ConstraintCalls + b.ConstraintCalls,
        a.ContactCalls + b.ContactCalls,
        a.ContactPairs + b.ContactPairs,
        a.Contacts + b.Contacts);

    /// <summary>True when every time and count is the same.</summary>
    public static bool operator ==(StepProfile a, StepProfile b) => a.Equals(b);

    /// <summary>True when some time or count differs.</summary>
    public static bool operator !=(StepProfile a, StepProfile b) => !a.Equals(b);

    /// <inheritdoc />
    public bool Equals(StepProfile other) =>
        TotalSeconds.Equals(other.TotalSeconds) && ForceSeconds.Equals(other.ForceSeconds)
        && ConstraintSeconds.Equals(other.ConstraintSeconds) && ContactSeconds.Equals(other.ContactSeconds)
        && BroadPhaseSeconds.Equals(other.BroadPhaseSeconds) && ForceEvaluations == other.ForceEvaluations
        && JacobianProducts == other.JacobianProducts && Substeps == other.Substeps
        && ConstraintCalls == other.ConstraintCalls && ContactCalls == other.ContactCalls
        && ContactPairs == other.ContactPairs && Contacts == other.Contacts;

    /// <inheritdoc />
    public override bool Equals(object? obj) => obj is StepProfile other && Equals(other);

    /// <inheritdoc />
    public override int GetHashCode() =>
        (TotalSeconds.GetHashCode() * 31) ^ (ForceEvaluations * 17) ^ (ConstraintCalls * 7) ^ ContactCalls;

    /// <summary>One line: each stage's time in microseconds, and the counts.</summary>
    public override string ToString() => string.Format(
        System.Globalization.CultureInfo.InvariantCulture,
        "total {0:F1} us: integration {1:F1}, forces {2:F1} ({3} evaluations, {4} products), constraints {5:F1} ({6} calls, {7} substeps), contacts {8:F1} ({9} calls, broad phase {10:F1}, {11} pairs, {12} contacts)",
        TotalSeconds * 1e6,
        IntegrationSeconds * 1e6,
        ForceSeconds * 1e6,
        ForceEvaluations,
        JacobianProducts,
        ConstraintSeconds * 1e6,
        ConstraintCalls,
        Substeps,
        ContactSeconds * 1e6,
        ContactCalls,
        BroadPhaseSeconds * 1e6,
        ContactPairs,
        Contacts);
}
