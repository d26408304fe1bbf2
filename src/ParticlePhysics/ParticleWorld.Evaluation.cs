using System;

namespace ParticlePhysics;

// The force-based path's evaluation: dy/dt = [v | F / m], the generators and then the constraint forces into one
// accumulator.
public sealed partial class ParticleWorld : ISecondOrderSystem
{
    /// <summary>Writes dy/dt = [v | F / m] for the state <paramref name="state"/> at time <paramref name="time"/>.</summary>
    public void Evaluate(double time, ReadOnlySpan<double> state, Span<double> derivative)
    {
        var n = 3 * _count;
        if (state.Length != 2 * n || derivative.Length != 2 * n)
        {
            throw new ArgumentException(
                $"state and derivative must have {2 * n} values; got {state.Length} and {derivative.Length}.");
        }

        var velocities = state.Slice(n, n);
        velocities.CopyTo(derivative);
        ComputeAccelerations(time, state.Slice(0, n), velocities, derivative.Slice(n, n));
    }

    /// <summary>Writes the accelerations F / m (0 for pinned particles) for the given positions and velocities.</summary>
    public void ComputeAccelerations(
        double time, ReadOnlySpan<double> positions, ReadOnlySpan<double> velocities, Span<double> accelerations)
    {
        var n = 3 * _count;
        if (positions.Length != n || velocities.Length != n || accelerations.Length != n)
        {
            throw new ArgumentException(
                $"positions, velocities and accelerations must have {n} values each.");
        }

        _ = AccumulateForces(time, positions, velocities);
        var count = n / 3;
        if (_forces.Length < n || _inverseMasses.Length < count)
        {
            // A generator that added particles while it was evaluated (a step forbids it; a bare Evaluate cannot).
            throw new InvalidOperationException("The world changed while its forces were being evaluated.");
        }

        unsafe
        {
            // The accumulator itself, an array (pinning the read-only span AccumulateForces returns would not bind on
            // Mono). The loop runs over the n values checked above, whatever a generator did to the world meanwhile.
            fixed (double* f = _forces, w = _inverseMasses, a = accelerations)
            {
                for (var i = 0; i < count; i++)
                {
                    var o = 3 * i;
                    a[o] = f[o] * w[i];
                    a[o + 1] = f[o + 1] * w[i];
                    a[o + 2] = f[o + 2] * w[i];
                }
            }
        }
    }

    /// <summary>
    /// Clears the force accumulator and lets every generator add into it, for the given positions and velocities, then
    /// every constraint set that acts through forces (<see cref="IConstraintForces"/>: rods, taut cables) adds its
    /// constraint forces for those applied forces. Returns the accumulator (3 values per particle), valid until the next
    /// evaluation.
    /// </summary>
    public ReadOnlySpan<double> AccumulateForces(double time, ReadOnlySpan<double> positions, ReadOnlySpan<double> velocities)
    {
        var n = 3 * _count;
        var forces = _forces.AsSpan(0, n);
        forces.Clear();
        var view = new ParticleState(time, positions, velocities, Masses, InverseMasses, Runner);
        var started = ProfileStart();
        for (var g = 0; g < _forceGenerators.Count; g++)
        {
            _forceGenerators[g].AddForces(in view, forces);
        }

        var generated = ProfileEvaluation(started);
        if (_constraintForces.Count > 0)
        {
            for (var c = 0; c < _constraintForces.Count; c++)
            {
                _constraintForces[c].AddConstraintForces(in view, forces);
            }

            ProfileConstraintForces(generated, _constraintForces.Count);
        }

        return forces;
    }
}
