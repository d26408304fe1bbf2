using System;
using ParticlePhysics.Internal;

namespace ParticlePhysics.Forces;

/// <summary>
/// Dashpots between pairs of particles, the course's "spring damping force": F_i = -c (v_i - v_j), F_j = -F_i.
/// They resist relative motion in every direction, dissipate energy, and conserve total momentum.
/// Jacobian: df_i/dv_i = df_j/dv_j = -c I, df_i/dv_j = c I.
/// </summary>
public sealed class Dampers : IForceGenerator, IBoundForce, IJacobianCouplings, IAppendOnlyCouplings
{
    private readonly ForceElements _pairs = new(1);
    private readonly ParticleWorld _system;
    private double _velocityScale;
    private LinearizationStamp _linearized;

    /// <summary>An empty set of dampers for the particles of <paramref name="system"/>.</summary>
    public Dampers(ParticleWorld system)
    {
        Guard.NotNull(system, nameof(system));
        _system = system;
    }

    /// <summary>The number of dampers.</summary>
    public int Count => _pairs.Count;

    object? IBoundForce.World => _system;

    /// <summary>Adds a damper between two different existing particles.</summary>
    /// <param name="first">One end (i).</param>
    /// <param name="second">The other end (j).</param>
    /// <param name="damping">c, in N s/m: a finite number &gt;= 0.</param>
    /// <returns>The index of the new damper.</returns>
    public int Add(int first, int second, double damping)
    {
        _system.ThrowIfStepping();
        Guard.ParticleIndex(first, _system.Count, nameof(first));
        Guard.ParticleIndex(second, _system.Count, nameof(second));
        Guard.DistinctParticles(first, second, nameof(second));
        Guard.NonNegativeFinite(damping, nameof(damping));
        Span<double> p = stackalloc double[] { damping };
        return _pairs.Add(first, second, p);
    }

    /// <summary>Changes the damping coefficient of a damper (a finite number &gt;= 0, in N s/m).</summary>
    public void SetDamping(int damper, double damping)
    {
        _system.ThrowIfStepping();
        _pairs.CheckIndex(damper, nameof(damper));
        Guard.NonNegativeFinite(damping, nameof(damping));
        _pairs.Parameters[damper] = damping;
    }

    /// <inheritdoc />
    public void AddForces(in ParticleState state, Span<double> forces) =>
        LinearPairTerms.AddScaledDifferences(_pairs, state.Velocities, forces, 1.0);

    /// <inheritdoc />
    public void Linearize(
        in ParticleState state, double positionScale, double velocityScale, Span<double> positionJacobianTimesVelocity)
    {
        _velocityScale = velocityScale;
        _linearized.Record(_pairs.Count, 0);
    }

    /// <inheritdoc />
    public void AddJacobianProduct(ReadOnlySpan<double> w, Span<double> result)
    {
        _linearized.Check(nameof(Dampers), _pairs.Count, 0);
        LinearPairTerms.AddScaledDifferences(_pairs, w, result, _velocityScale);
    }

    /// <inheritdoc />
    public void AddDiagonalBlocks(Span<double> blocks)
    {
        _linearized.Check(nameof(Dampers), _pairs.Count, 0);
        LinearPairTerms.AddDiagonalBlocks(_pairs, blocks, _velocityScale);
    }

    /// <inheritdoc />
    public int CouplingCount => _pairs.Count;

    /// <inheritdoc />
    public void WriteCouplings(Span<int> first, Span<int> second) => LinearPairTerms.WriteCouplings(_pairs, first, second);

    /// <inheritdoc />
    public void AddCouplingBlocks(Span<double> destination, ReadOnlySpan<int> forwardBlock, ReadOnlySpan<int> backwardBlock)
    {
        _linearized.Check(nameof(Dampers), _pairs.Count, 0);
        LinearPairTerms.AddCouplingBlocks(_pairs, destination, forwardBlock, backwardBlock, _velocityScale);
    }
}
