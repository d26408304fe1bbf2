using System;
using System.Collections.Generic;
using ParticlePhysics.Internal;

namespace ParticlePhysics;

// The implicit path: the forces' Jacobian at a state (linearise, products, diagonal blocks, couplings), gathered
// over the generators and the constraint sets that act through forces.
public sealed partial class ParticleWorld : ILinearizableSystem, ICouplingRevision, IJacobianProductTail
{
    // The implicit stepper's linearisation (ILinearizableSystem): the generators linearised at the last Linearize,
    // and the finite-difference wrappers of those that supply no Jacobian of their own, kept while they are added.
    private readonly List<IForceJacobian> _linearized = new();
    private readonly List<int> _linearizedSource = new(); // the index of each entry's generator, increasing
    private readonly Dictionary<IForceGenerator, FiniteDifferenceJacobian> _finiteDifference = new();

    // Bumped whenever particles or generators are added or removed: products and blocks need a Linearize of the
    // world as it is (its buffers' sizes and its generators' linearisations follow the particles and the generators).
    private int _structureVersion;
    private int _linearizedVersion = -1;

    // This world's number among the worlds of the process (ICouplingRevision: a revision no other world gives).
    private static long _worldsCreated;
    private readonly long _worldNumber = System.Threading.Interlocked.Increment(ref _worldsCreated);

    /// <inheritdoc />
    /// <remarks>
    /// Linearises every generator that implements <see cref="IForceJacobian"/>, in the order they were added; the
    /// others enter J by finite differences when <paramref name="userForces"/> asks for it, and not at all otherwise
    /// (they then act on the step explicitly, through <see cref="AccumulateForces"/>).
    /// </remarks>
    void ILinearizableSystem.Linearize(
        double time,
        ReadOnlySpan<double> positions,
        ReadOnlySpan<double> velocities,
        double positionScale,
        double velocityScale,
        UserForceTreatment userForces,
        Span<double> positionJacobianTimesVelocity)
    {
        CheckLinearization(positions.Length, velocities.Length, positionJacobianTimesVelocity.Length);
        CollectLinearized(userForces);
        if (_linearized.Count > 0 && _linearizedSource[_linearized.Count - 1] >= _forceGenerators.Count)
        {
            // A constraint set linearises the multipliers of its last forces: evaluate them at this state first.
            _ = AccumulateForces(time, positions, velocities);
        }

        var view = new ParticleState(time, positions, velocities, Masses, InverseMasses, Runner);
        var started = ProfileStart();
        for (var j = 0; j < _linearized.Count; j++)
        {
            _linearized[j].Linearize(view, positionScale, velocityScale, positionJacobianTimesVelocity);
        }

        ProfileForces(started);
        _linearizedVersion = _structureVersion;
    }

    /// <inheritdoc />
    /// <remarks>
    /// Each generator in the order they were added: one that implements <see cref="IForceLinearization"/> in one pass,
    /// the others by AddForces, then (when they enter J: <see cref="IForceJacobian"/>, or finite differences when
    /// <paramref name="userForces"/> asks for it) Linearize and AddDiagonalBlocks; then the constraint forces. The
    /// forces, (df/dx) v and the blocks are separate accumulators, each receiving the generators' terms in the same
    /// order as the three separate calls, so the results are theirs to the last bit.
    /// </remarks>
    ReadOnlySpan<double> ILinearizableSystem.AccumulateForcesAndLinearize(
        double time,
        ReadOnlySpan<double> positions,
        ReadOnlySpan<double> velocities,
        double positionScale,
        double velocityScale,
        UserForceTreatment userForces,
        Span<double> positionJacobianTimesVelocity,
        Span<double> diagonalBlocks)
    {
        CheckLinearization(positions.Length, velocities.Length, positionJacobianTimesVelocity.Length);
        if (diagonalBlocks.Length < 9 * _count)
        {
            throw new ArgumentException(
                $"diagonalBlocks must hold 9 values per particle, {9 * _count}; it holds {diagonalBlocks.Length}.", nameof(diagonalBlocks));
        }

        CollectLinearized(userForces);
        var n = 3 * _count;
        var forces = _forces.AsSpan(0, n);
        forces.Clear();
        var view = new ParticleState(time, positions, velocities, Masses, InverseMasses, Runner);
        var started = ProfileStart();
        var next = 0; // the next entry of _linearized: the generators' own Jacobians and wrappers, in generator order
        for (var g = 0; g < _forceGenerators.Count; g++)
        {
            var generator = _forceGenerators[g];
            var jacobian = next < _linearized.Count && _linearizedSource[next] == g ? _linearized[next++] : null;
            if (jacobian is IForceLinearization fused && ReferenceEquals(fused, generator))
            {
                fused.AddForcesAndLinearize(in view, positionScale, velocityScale, forces, positionJacobianTimesVelocity, diagonalBlocks);
                continue;
            }

            generator.AddForces(in view, forces);
            if (jacobian is not null)
            {
                jacobian.Linearize(view, positionScale, velocityScale, positionJacobianTimesVelocity);
                jacobian.AddDiagonalBlocks(diagonalBlocks);
            }
        }

        var generated = ProfileEvaluation(started);
        for (var c = 0; c < _constraintForces.Count; c++)
        {
            _constraintForces[c].AddConstraintForces(in view, forces);
            if (next < _linearized.Count && _linearizedSource[next] == _forceGenerators.Count + c)
            {
                // Right after its forces at this state: a constraint set linearises the multipliers it just solved for.
                var jacobian = _linearized[next++];
                jacobian.Linearize(view, positionScale, velocityScale, positionJacobianTimesVelocity);
                jacobian.AddDiagonalBlocks(diagonalBlocks);
            }
        }

        if (_constraintForces.Count > 0)
        {
            ProfileConstraintForces(generated, _constraintForces.Count);
        }

        _linearizedVersion = _structureVersion;
        return forces;
    }

    /// <summary>Checks the buffers of a linearisation against the world's size.</summary>
    private void CheckLinearization(int positions, int velocities, int positionJacobianTimesVelocity)
    {
        var n = 3 * _count;
        if (positions != n || velocities != n || positionJacobianTimesVelocity != n)
        {
            throw new ArgumentException(
                $"positions, velocities and positionJacobianTimesVelocity must have {n} values each; got "
                + $"{positions}, {velocities} and {positionJacobianTimesVelocity}.");
        }
    }

    /// <summary>
    /// The generators that enter J, in the order they were added: those that implement <see cref="IForceJacobian"/>,
    /// and the others wrapped in finite differences when <paramref name="userForces"/> asks for it; then the constraint
    /// sets that act through forces (<see cref="IConstraintForces"/>) and implement <see cref="IForceJacobian"/>.
    /// </summary>
    private void CollectLinearized(UserForceTreatment userForces)
    {
        _linearizedVersion = -1;
        _linearized.Clear();
        _linearizedSource.Clear();
        for (var g = 0; g < _forceGenerators.Count; g++)
        {
            var generator = _forceGenerators[g];
            if (generator is IForceJacobian jacobian)
            {
                _linearized.Add(jacobian);
                _linearizedSource.Add(g);
            }
            else if (userForces == UserForceTreatment.FiniteDifference)
            {
                if (!_finiteDifference.TryGetValue(generator, out var wrapper))
                {
                    wrapper = new FiniteDifferenceJacobian(generator);
                    _finiteDifference.Add(generator, wrapper);
                }

                _linearized.Add(wrapper);
                _linearizedSource.Add(g);
            }
        }

        // Then the constraint sets that act through forces and linearise them (rods: their tensions' geometric
        // stiffness), numbered after the generators.
        for (var c = 0; c < _constraintForces.Count; c++)
        {
            if (_constraintForces[c] is IForceJacobian jacobian)
            {
                _linearized.Add(jacobian);
                _linearizedSource.Add(_forceGenerators.Count + c);
            }
        }
    }

    /// <inheritdoc />
    /// <exception cref="InvalidOperationException">
    /// No Linearize yet, or particles or generators were added or removed since the last one.
    /// </exception>
    void ILinearizableSystem.AddJacobianProduct(ReadOnlySpan<double> w, Span<double> result)
    {
        CheckLinearized(w.Length, result.Length, 3);
        var started = ProfileStart();
        for (var j = 0; j < _linearized.Count; j++)
        {
            _linearized[j].AddJacobianProduct(w, result);
        }

        ProfileProduct(started);
    }

    /// <inheritdoc />
    bool IJacobianProductTail.TryGetUniformTail(out double coefficient)
    {
        var tail = UniformTail(out coefficient);
        return tail >= 0;
    }

    /// <inheritdoc />
    /// <exception cref="InvalidOperationException">
    /// No Linearize yet, or particles or generators were added or removed since the last one, or no uniform tail.
    /// </exception>
    void IJacobianProductTail.AddJacobianProductBeforeTail(ReadOnlySpan<double> w, Span<double> result)
    {
        CheckLinearized(w.Length, result.Length, 3);
        var tail = UniformTail(out _);
        if (tail < 0)
        {
            throw new InvalidOperationException("The world's Jacobian product has no uniform tail: use AddJacobianProduct.");
        }

        var started = ProfileStart();
        for (var j = 0; j < tail; j++)
        {
            _linearized[j].AddJacobianProduct(w, result);
        }

        ProfileProduct(started);
    }

    /// <summary>
    /// The index among the linearised generators of the last one whose product does anything, when that product is
    /// c w on every coordinate (with <paramref name="coefficient"/> c), else -1. The generators after it add nothing.
    /// </summary>
    private int UniformTail(out double coefficient)
    {
        coefficient = 0.0;
        if (_linearizedVersion != _structureVersion)
        {
            return -1;
        }

        // Bounded by the generators; the first from the end that is not a product of nothing decides.
        for (var j = _linearized.Count - 1; j >= 0; j--)
        {
            if (_linearized[j] is not IUniformJacobianProduct uniform || !uniform.TryGetUniformProduct(out var c, out var none))
            {
                return -1;
            }

            if (!none)
            {
                coefficient = c;
                return j;
            }
        }

        return -1;
    }

    /// <inheritdoc />
    /// <exception cref="InvalidOperationException">
    /// No Linearize yet, or particles or generators were added or removed since the last one.
    /// </exception>
    void ILinearizableSystem.AddDiagonalBlocks(Span<double> blocks)
    {
        CheckLinearized(blocks.Length, blocks.Length, 9);
        var started = ProfileStart();
        for (var j = 0; j < _linearized.Count; j++)
        {
            _linearized[j].AddDiagonalBlocks(blocks);
        }

        ProfileForces(started);
    }

    /// <inheritdoc />
    /// <remarks>The couplings of the linearised generators that state theirs (<see cref="IJacobianCouplings"/>), in order.</remarks>
    int ILinearizableSystem.CouplingCount
    {
        get
        {
            var count = 0;
            for (var j = 0; j < _linearized.Count; j++)
            {
                if (_linearized[j] is IJacobianCouplings couplings)
                {
                    count += couplings.CouplingCount;
                }
            }

            return count;
        }
    }

    /// <inheritdoc />
    /// <remarks>
    /// The revision is the world's number among the process's worlds (high 32 bits) and its structure version, which
    /// every added or removed force and particle changes (low 32 bits); the forces are those of the last
    /// linearisation, as for <see cref="ILinearizableSystem.CouplingCount"/>.
    /// </remarks>
    bool ICouplingRevision.TryGetCouplingRevision(out long revision)
    {
        revision = (_worldNumber << 32) | (uint)_structureVersion;
        for (var j = 0; j < _linearized.Count; j++)
        {
            if (_linearized[j] is IJacobianCouplings and not IAppendOnlyCouplings)
            {
                return false;
            }
        }

        return true;
    }

    /// <inheritdoc />
    void ILinearizableSystem.WriteCouplings(Span<int> first, Span<int> second)
    {
        var offset = 0;
        for (var j = 0; j < _linearized.Count; j++)
        {
            if (_linearized[j] is IJacobianCouplings couplings)
            {
                var count = couplings.CouplingCount;
                couplings.WriteCouplings(first.Slice(offset, count), second.Slice(offset, count));
                offset += count;
            }
        }
    }

    /// <inheritdoc />
    void ILinearizableSystem.AddCouplingBlocks(Span<double> destination, ReadOnlySpan<int> forwardBlock, ReadOnlySpan<int> backwardBlock)
    {
        var offset = 0;
        for (var j = 0; j < _linearized.Count; j++)
        {
            if (_linearized[j] is IJacobianCouplings couplings)
            {
                var count = couplings.CouplingCount;
                couplings.AddCouplingBlocks(destination, forwardBlock.Slice(offset, count), backwardBlock.Slice(offset, count));
                offset += count;
            }
        }
    }

    private void CheckLinearized(int input, int output, int perParticle)
    {
        if (_linearizedVersion != _structureVersion)
        {
            throw new InvalidOperationException(_linearizedVersion < 0
                ? "Jacobian products and blocks need a Linearize of the world first."
                : "Particles or force generators were added or removed since the last Linearize: linearise again.");
        }

        var needed = perParticle * _count;
        if (input != needed || output != needed)
        {
            throw new ArgumentException($"The buffers must hold {needed} values ({perParticle} per particle); got {input} and {output}.");
        }
    }
}
