using System;
using System.Collections.Generic;
using ParticlePhysics.Internal;

namespace ParticlePhysics;

// The world's force generators and constraint sets: what it holds besides the particles, added and removed between
// steps.
public sealed partial class ParticleWorld
{
    private readonly List<IForceGenerator> _forceGenerators = new();
    private readonly List<IConstraintSet> _constraintSets = new();

    // The sets that add constraint forces at every evaluation (rods under the force-based integrators).
    private readonly List<IConstraintForces> _constraintForces = new();

    /// <summary>The force generators, in the order they are evaluated.</summary>
    public IReadOnlyList<IForceGenerator> Forces => _forceGenerators;

    /// <summary>The constraint sets (rods, cables, contacts, ...), in the order their stage applies them.</summary>
    public IReadOnlyList<IConstraintSet> Constraints => _constraintSets;

    /// <summary>Adds a force generator; it acts from the next evaluation on.</summary>
    /// <exception cref="ArgumentException">The generator is already in this system, or names the particles of another one.</exception>
    public void AddForce(IForceGenerator generator)
    {
        ThrowIfStepping();
        Guard.NotNull(generator, nameof(generator));
        if (_forceGenerators.Contains(generator))
        {
            throw new ArgumentException("This force generator is already in the system.", nameof(generator));
        }

        if (generator is IBoundForce { World: { } owner } && !ReferenceEquals(owner, this))
        {
            throw new ArgumentException(
                "This force generator was built for another particle system: its particle indices refer to that one.",
                nameof(generator));
        }

        _forceGenerators.Add(generator);
        WakeAll();
        _unprojectedStale = true;
        _structureVersion++;
    }

    /// <summary>Removes a force generator; returns false when it was not in the system.</summary>
    public bool RemoveForce(IForceGenerator generator)
    {
        ThrowIfStepping();
        if (!_forceGenerators.Remove(generator))
        {
            return false;
        }

        WakeAll();
        _ = _finiteDifference.Remove(generator);
        _linearized.Clear(); // a later product must not reach a removed generator; the next Linearize rebuilds it
        _linearizedSource.Clear();
        _unprojectedStale = true;
        _structureVersion++;
        return true;
    }

    /// <summary>Adds a constraint set; the constraint stage applies it from the next step on, after the sets before it.</summary>
    /// <exception cref="ArgumentException">The set is already in this world.</exception>
    public void AddConstraints(IConstraintSet constraints)
    {
        ThrowIfStepping();
        Guard.NotNull(constraints, nameof(constraints));
        if (_constraintSets.Contains(constraints))
        {
            throw new ArgumentException("This constraint set is already in the world.", nameof(constraints));
        }

        _constraintSets.Add(constraints);
        WakeAll();
        if (constraints is IConstraintForces forces)
        {
            _constraintForces.Add(forces);
            if (constraints is IForceJacobian)
            {
                _structureVersion++; // it enters J: a product needs a Linearize that saw it
            }
        }

        _unprojectedStale = true;
    }

    /// <summary>Removes a constraint set; returns false when it was not in the world.</summary>
    public bool RemoveConstraints(IConstraintSet constraints)
    {
        ThrowIfStepping();
        if (!_constraintSets.Remove(constraints))
        {
            return false;
        }

        WakeAll();
        if (constraints is IConstraintForces forces)
        {
            _ = _constraintForces.Remove(forces);
            if (constraints is IForceJacobian)
            {
                _linearized.Clear(); // as for a removed generator: no later product may reach it
                _linearizedSource.Clear();
                _structureVersion++;
            }
        }

        _unprojectedStale = true;
        return true;
    }
}
