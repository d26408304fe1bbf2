using System;
using ParticlePhysics.Internal;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Forces;

/// <summary>
/// Hooke springs of zero rest length, the course's F = -k x: between particles i and j, F_i = -k (x_i - x_j) and
/// F_j = -F_i; between particle i and a fixed anchor a, F_i = -k (x_i - a). The force is linear in the positions
/// (which makes the mass-spring-damper exactly solvable). Potential energy: k |x_i - x_j|^2 / 2 per spring.
/// Jacobian: df_i/dx_i = -k I, df_i/dx_j = k I (constant, so implicit Euler is exact backward Euler for it).
/// </summary>
public sealed class ZeroLengthSprings : IForceGenerator, IPotentialEnergy, IBoundForce, IJacobianCouplings, ISpringElements, IAppendOnlyCouplings
{
    // Pair parameters: k. Anchored parameters: ax, ay, az, k.
    private readonly ForceElements _pairs = new(1);
    private readonly ForceElements _anchored = new(4);
    private readonly ParticleWorld _system;
    private double _positionScale;
    private int _topologyVersion;
    private int _parameterVersion;
    private LinearizationStamp _linearized;

    /// <summary>An empty set of springs for the particles of <paramref name="system"/>.</summary>
    public ZeroLengthSprings(ParticleWorld system)
    {
        Guard.NotNull(system, nameof(system));
        _system = system;
    }

    /// <summary>The number of springs between two particles.</summary>
    public int Count => _pairs.Count;

    /// <summary>The number of springs between a particle and a fixed anchor.</summary>
    public int AnchoredCount => _anchored.Count;

    object? IBoundForce.World => _system;

    /// <inheritdoc />
    public int TopologyVersion => _topologyVersion;

    /// <inheritdoc />
    public int ParameterVersion => _parameterVersion;

    /// <inheritdoc />
    int ISpringElements.PairCount => _pairs.Count;

    /// <inheritdoc />
    /// <remarks>Each spring reads as (k, 0, 0): rest length 0 and no damping.</remarks>
    public void CopyPairs(Span<int> first, Span<int> second, Span<double> parameters)
    {
        _pairs.First.AsSpan(0, _pairs.Count).CopyTo(first);
        _pairs.Second.AsSpan(0, _pairs.Count).CopyTo(second);
        for (var s = 0; s < _pairs.Count; s++)
        {
            parameters[3 * s] = _pairs.Parameters[s];
            parameters[(3 * s) + 1] = 0.0;
            parameters[(3 * s) + 2] = 0.0;
        }
    }

    /// <inheritdoc />
    /// <remarks>Each spring reads as (ax, ay, az, k, 0, 0): rest length 0 and no damping.</remarks>
    public void CopyAnchored(Span<int> particle, Span<double> parameters)
    {
        _anchored.First.AsSpan(0, _anchored.Count).CopyTo(particle);
        for (var s = 0; s < _anchored.Count; s++)
        {
            _anchored.Parameters.AsSpan(4 * s, 4).CopyTo(parameters.Slice(6 * s, 4));
            parameters[(6 * s) + 4] = 0.0;
            parameters[(6 * s) + 5] = 0.0;
        }
    }

    /// <summary>Adds a spring between two different existing particles.</summary>
    /// <param name="first">One end.</param>
    /// <param name="second">The other end.</param>
    /// <param name="stiffness">k, in N/m: a finite number &gt;= 0.</param>
    /// <returns>The index of the new spring among the particle-particle springs.</returns>
    public int Add(int first, int second, double stiffness)
    {
        _system.ThrowIfStepping();
        Guard.ParticleIndex(first, _system.Count, nameof(first));
        Guard.ParticleIndex(second, _system.Count, nameof(second));
        Guard.DistinctParticles(first, second, nameof(second));
        Guard.NonNegativeFinite(stiffness, nameof(stiffness));
        Span<double> p = stackalloc double[] { stiffness };
        _topologyVersion++;
        return _pairs.Add(first, second, p);
    }

    /// <summary>Adds a spring between an existing particle and a fixed anchor point.</summary>
    /// <param name="particle">The particle.</param>
    /// <param name="anchor">The anchor's position, in metres (it has zero velocity).</param>
    /// <param name="stiffness">k, in N/m: a finite number &gt;= 0.</param>
    /// <returns>The index of the new spring among the anchored springs.</returns>
    public int AddAnchored(int particle, Vector3d anchor, double stiffness)
    {
        _system.ThrowIfStepping();
        Guard.ParticleIndex(particle, _system.Count, nameof(particle));
        Guard.Finite(anchor, nameof(anchor));
        Guard.NonNegativeFinite(stiffness, nameof(stiffness));
        Span<double> p = stackalloc double[] { anchor.X, anchor.Y, anchor.Z, stiffness };
        _topologyVersion++;
        return _anchored.Add(particle, -1, p);
    }

    /// <summary>The two particles joined by a particle-particle spring.</summary>
    /// <param name="spring">The index of the spring among the particle-particle springs, 0 to <see cref="Count"/> - 1.</param>
    public (int First, int Second) GetEnds(int spring)
    {
        _pairs.CheckIndex(spring, nameof(spring));
        return (_pairs.First[spring], _pairs.Second[spring]);
    }

    /// <summary>The particle and the anchor point of an anchored spring (what a renderer draws).</summary>
    /// <param name="spring">The index of the spring among the anchored springs, 0 to <see cref="AnchoredCount"/> - 1.</param>
    public (int Particle, Vector3d Anchor) GetAnchoredSpring(int spring)
    {
        _anchored.CheckIndex(spring, nameof(spring));
        var p = _anchored.Parameters;
        return (_anchored.First[spring], new Vector3d(p[4 * spring], p[(4 * spring) + 1], p[(4 * spring) + 2]));
    }

    /// <summary>Changes the stiffness of a particle-particle spring.</summary>
    public void SetStiffness(int spring, double stiffness)
    {
        _system.ThrowIfStepping();
        _pairs.CheckIndex(spring, nameof(spring));
        Guard.NonNegativeFinite(stiffness, nameof(stiffness));
        _pairs.Parameters[spring] = stiffness;
        _parameterVersion++;
    }

    /// <summary>Moves the anchor of an anchored spring (to attach a particle to a point that the host moves).</summary>
    public void SetAnchor(int spring, Vector3d anchor)
    {
        _system.ThrowIfStepping();
        _anchored.CheckIndex(spring, nameof(spring));
        Guard.Finite(anchor, nameof(anchor));
        _anchored.Parameters[4 * spring] = anchor.X;
        _anchored.Parameters[(4 * spring) + 1] = anchor.Y;
        _anchored.Parameters[(4 * spring) + 2] = anchor.Z;
        _parameterVersion++;
    }

    /// <inheritdoc />
    public void AddForces(in ParticleState state, Span<double> forces)
    {
        var x = state.Positions.ForReading();
        LinearPairTerms.AddScaledDifferences(_pairs, x, forces, 1.0);

        var anchoredParticle = _anchored.First;
        var p = _anchored.Parameters;
        for (var s = 0; s < _anchored.Count; s++)
        {
            var a = 3 * anchoredParticle[s];
            var ks = p[(4 * s) + 3];
            forces[a] -= ks * (x[a] - p[4 * s]);
            forces[a + 1] -= ks * (x[a + 1] - p[(4 * s) + 1]);
            forces[a + 2] -= ks * (x[a + 2] - p[(4 * s) + 2]);
        }
    }

    /// <inheritdoc />
    public double PotentialEnergy(in ParticleState state)
    {
        var x = state.Positions.ForReading();
        var sum = 0.0;
        for (var s = 0; s < _pairs.Count; s++)
        {
            int a = 3 * _pairs.First[s], b = 3 * _pairs.Second[s];
            double dx = x[a] - x[b], dy = x[a + 1] - x[b + 1], dz = x[a + 2] - x[b + 2];
            sum += 0.5 * _pairs.Parameters[s] * ((dx * dx) + (dy * dy) + (dz * dz));
        }

        var p = _anchored.Parameters;
        for (var s = 0; s < _anchored.Count; s++)
        {
            var a = 3 * _anchored.First[s];
            double dx = x[a] - p[4 * s], dy = x[a + 1] - p[(4 * s) + 1], dz = x[a + 2] - p[(4 * s) + 2];
            sum += 0.5 * p[(4 * s) + 3] * ((dx * dx) + (dy * dy) + (dz * dz));
        }

        return sum;
    }

    /// <inheritdoc />
    public void Linearize(
        in ParticleState state, double positionScale, double velocityScale, Span<double> positionJacobianTimesVelocity)
    {
        _positionScale = positionScale;
        var v = state.Velocities.ForReading();
        LinearPairTerms.AddScaledDifferences(_pairs, v, positionJacobianTimesVelocity, 1.0);
        for (var s = 0; s < _anchored.Count; s++)
        {
            var a = 3 * _anchored.First[s];
            var k = _anchored.Parameters[(4 * s) + 3];
            for (var c = 0; c < 3; c++)
            {
                positionJacobianTimesVelocity[a + c] -= k * v[a + c];
            }
        }

        _linearized.Record(_pairs.Count, _anchored.Count);
    }

    /// <inheritdoc />
    public void AddJacobianProduct(ReadOnlySpan<double> w, Span<double> result)
    {
        _linearized.Check(nameof(ZeroLengthSprings), _pairs.Count, _anchored.Count);
        var wr = w.ForReading();
        LinearPairTerms.AddScaledDifferences(_pairs, w, result, _positionScale);
        for (var s = 0; s < _anchored.Count; s++)
        {
            var a = 3 * _anchored.First[s];
            var k = -_anchored.Parameters[(4 * s) + 3] * _positionScale;
            for (var c = 0; c < 3; c++)
            {
                result[a + c] += k * wr[a + c];
            }
        }
    }

    /// <inheritdoc />
    public void AddDiagonalBlocks(Span<double> blocks)
    {
        _linearized.Check(nameof(ZeroLengthSprings), _pairs.Count, _anchored.Count);
        LinearPairTerms.AddDiagonalBlocks(_pairs, blocks, _positionScale);
        for (var s = 0; s < _anchored.Count; s++)
        {
            JacobianBlocks.AddIsotropic(blocks, _anchored.First[s], -_anchored.Parameters[(4 * s) + 3] * _positionScale);
        }
    }

    /// <inheritdoc />
    public int CouplingCount => _pairs.Count;

    /// <inheritdoc />
    public void WriteCouplings(Span<int> first, Span<int> second) => LinearPairTerms.WriteCouplings(_pairs, first, second);

    /// <inheritdoc />
    public void AddCouplingBlocks(Span<double> destination, ReadOnlySpan<int> forwardBlock, ReadOnlySpan<int> backwardBlock)
    {
        _linearized.Check(nameof(ZeroLengthSprings), _pairs.Count, _anchored.Count);
        LinearPairTerms.AddCouplingBlocks(_pairs, destination, forwardBlock, backwardBlock, _positionScale);
    }
}
