using System;
using System.Collections.Generic;
using ParticlePhysics.Internal;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Forces;

/// <summary>
/// Linear (viscous) drag, the course's "frottements fluides": F_i = -lambda v_i, on every particle or on a chosen
/// set. With gravity alone it gives the free fall of characteristic time tau = m / lambda.
/// Jacobian: df_i/dv_i = -lambda I (linear, so implicit Euler is exact backward Euler for it).
/// </summary>
public sealed class LinearDrag : IParticleLinks, IForceGenerator, IBoundForce, IForceJacobian, IUniformJacobianProduct
{
    private readonly int[]? _particles;
    private readonly ParticleWorld? _system;
    private double _coefficient;
    private int _revision;
    private double _linearized;
    private LinearizationStamp _stamp;

    /// <summary>Drag on every particle of whichever system the generator is added to.</summary>
    /// <param name="coefficient">lambda, in N s/m: a finite number &gt;= 0.</param>
    public LinearDrag(double coefficient)
    {
        Guard.NonNegativeFinite(coefficient, nameof(coefficient));
        _coefficient = coefficient;
    }

    /// <summary>Drag on the chosen particles of <paramref name="system"/> only.</summary>
    /// <param name="coefficient">lambda, in N s/m: a finite number &gt;= 0.</param>
    /// <param name="system">The particle system the indices refer to.</param>
    /// <param name="particles">The particles to drag; each must exist in <paramref name="system"/>.</param>
    public LinearDrag(double coefficient, ParticleWorld system, IEnumerable<int> particles)
    {
        Guard.NonNegativeFinite(coefficient, nameof(coefficient));
        Guard.NotNull(system, nameof(system));
        Guard.NotNull(particles, nameof(particles));
        var list = new List<int>(particles);
        foreach (var p in list)
        {
            Guard.ParticleIndex(p, system.Count, nameof(particles));
        }

        _coefficient = coefficient;
        _system = system;
        _particles = list.ToArray();
    }

    /// <inheritdoc />
    public int Revision => _revision;

    /// <inheritdoc />
    /// <remarks>Drag acts on each particle alone: it links none.</remarks>
    public void AddLinks(ParticleIslands islands)
    {
    }

    /// <summary>lambda, in N s/m; can be changed between steps (a finite number &gt;= 0).</summary>
    public double Coefficient
    {
        get => _coefficient;
        set
        {
            _system?.ThrowIfStepping(); // a drag on named particles knows its world; one on every particle does not
            Guard.NonNegativeFinite(value, nameof(Coefficient));
            _coefficient = value;
            _revision++;
        }
    }

    /// <summary>The particles dragged, or null when the drag acts on every particle.</summary>
    public IReadOnlyList<int>? Particles => _particles;

    object? IBoundForce.World => _system;

    /// <inheritdoc />
    public void AddForces(in ParticleState state, Span<double> forces)
    {
        var v = state.Velocities.ForReading();
        var lambda = _coefficient;
        if (_particles is null)
        {
            VectorKernels.SubtractScaled(forces, v, lambda);
            return;
        }

        foreach (var p in _particles)
        {
            var o = 3 * p;
            forces[o] -= lambda * v[o];
            forces[o + 1] -= lambda * v[o + 1];
            forces[o + 2] -= lambda * v[o + 2];
        }
    }

    /// <inheritdoc />
    public void Linearize(
        in ParticleState state, double positionScale, double velocityScale, Span<double> positionJacobianTimesVelocity)
    {
        _linearized = -_coefficient * velocityScale;
        _stamp.Record(0, 0);
    }

    /// <inheritdoc />
    bool IUniformJacobianProduct.TryGetUniformProduct(out double coefficient, out bool none)
    {
        _stamp.Check(nameof(LinearDrag), 0, 0);
        coefficient = _linearized;
        none = false;
        return _particles is null; // (the product below: result[k] += c w[k] on every k, as VectorKernels.AddScaled adds it)
    }

    /// <inheritdoc />
    public void AddJacobianProduct(ReadOnlySpan<double> w, Span<double> result)
    {
        _stamp.Check(nameof(LinearDrag), 0, 0);
        var wr = w.ForReading();
        var c = _linearized;
        if (_particles is null)
        {
            VectorKernels.AddScaled(result, wr, c); // result[k] += c w[k], with SIMD where the runtime has it: the same bits
            return;
        }

        foreach (var p in _particles)
        {
            var o = 3 * p;
            result[o] += c * wr[o];
            result[o + 1] += c * wr[o + 1];
            result[o + 2] += c * wr[o + 2];
        }
    }

    /// <inheritdoc />
    public void AddDiagonalBlocks(Span<double> blocks)
    {
        _stamp.Check(nameof(LinearDrag), 0, 0);
        var c = _linearized;
        if (_particles is null)
        {
            for (var b = 0; b < blocks.Length; b += 9)
            {
                blocks[b] += c;
                blocks[b + 4] += c;
                blocks[b + 8] += c;
            }

            return;
        }

        foreach (var p in _particles)
        {
            JacobianBlocks.AddIsotropic(blocks, p, c);
        }
    }
}
