using System;
using System.Collections.Generic;

namespace ParticlePhysics;

// The position-based path (xpbd): the accelerations of the forces no set projects, and each substep's projection and
// velocity passes over the constraint sets.
public sealed partial class ParticleWorld : IPositionBasedSystem
{
    // The generators that no set projects (what xpbd's predictions see), rebuilt when generators or sets change.
    private readonly List<IForceGenerator> _unprojected = new();
    private bool _unprojectedStale = true;

    /// <inheritdoc />
    void IPositionBasedSystem.ComputeUnprojectedAccelerations(
        double time, ReadOnlySpan<double> positions, ReadOnlySpan<double> velocities, Span<double> accelerations)
    {
        var n = 3 * _count;
        if (positions.Length != n || velocities.Length != n || accelerations.Length != n)
        {
            throw new ArgumentException($"positions, velocities and accelerations must have {n} values each.");
        }

        if (_unprojectedStale)
        {
            CollectUnprojected();
        }

        var forces = _forces.AsSpan(0, n);
        forces.Clear();
        var view = new ParticleState(time, positions, velocities, Masses, InverseMasses, Runner);
        var started = ProfileStart();
        for (var g = 0; g < _unprojected.Count; g++)
        {
            _unprojected[g].AddForces(in view, forces);
        }

        _ = ProfileEvaluation(started);

        unsafe
        {
            // The accumulator and the inverse masses are arrays of at least n and n / 3 values, accelerations n. The
            // bound is n / 3, not _count: a force that added a particle during a bare call (outside a step, where the
            // world cannot refuse it) would otherwise make the loop write past the accelerations.
            var count = n / 3;
            fixed (double* f = _forces, w = _inverseMasses, a = accelerations)
            {
                double* fi = f, ai = a;
                for (var i = 0; i < count; i++, fi += 3, ai += 3)
                {
                    var wi = w[i];
                    ai[0] = fi[0] * wi;
                    ai[1] = fi[1] * wi;
                    ai[2] = fi[2] * wi;
                }
            }
        }
    }

    /// <inheritdoc />
    void IPositionBasedSystem.ProjectConstraints(
        double time,
        double dt,
        ReadOnlySpan<double> startPositions,
        ReadOnlySpan<double> startVelocities,
        Span<double> positions,
        Span<double> velocities)
    {
        var context = SubstepContext(time, dt, startPositions, startVelocities, positions, velocities);
        _substeps++;
        for (var c = 0; c < _constraintSets.Count; c++)
        {
            var set = _constraintSets[c];
            var started = ProfileStart();
            set.Project(in context);
            ProfileSet(set, started);
        }
    }

    /// <inheritdoc />
    void IPositionBasedSystem.SolveConstraintVelocities(
        double time,
        double dt,
        ReadOnlySpan<double> startPositions,
        ReadOnlySpan<double> startVelocities,
        Span<double> positions,
        Span<double> velocities)
    {
        var context = SubstepContext(time, dt, startPositions, startVelocities, positions, velocities);
        for (var c = 0; c < _constraintSets.Count; c++)
        {
            var set = _constraintSets[c];
            var started = ProfileStart();
            set.SolveVelocities(in context);
            ProfileSet(set, started);
        }
    }

    private ConstraintContext SubstepContext(
        double time,
        double dt,
        ReadOnlySpan<double> startPositions,
        ReadOnlySpan<double> startVelocities,
        Span<double> positions,
        Span<double> velocities)
    {
        Guard.PositiveFinite(dt, nameof(dt));
        return new ConstraintContext(
            time, dt, startPositions, startVelocities, positions, velocities, Masses, InverseMasses, Radii, Runner, kickDrift: false, SleepingForContext(_sleepActive));
    }

    /// <summary>The generators that no constraint set projects (<see cref="IForceProjection"/>), in their order.</summary>
    private void CollectUnprojected()
    {
        _unprojected.Clear();
        for (var g = 0; g < _forceGenerators.Count; g++)
        {
            var generator = _forceGenerators[g];
            var projected = false;
            for (var c = 0; c < _constraintSets.Count && !projected; c++)
            {
                projected = _constraintSets[c] is IForceProjection projection
                    && ReferenceEquals(projection.Force, generator);
            }

            if (!projected)
            {
                _unprojected.Add(generator);
            }
        }

        _unprojectedStale = false;
    }
}
