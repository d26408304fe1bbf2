using System;

namespace ParticlePhysics.Tests.Support;

/// <summary>What a <see cref="FaultyForce"/> does when it is armed.</summary>
public enum Fault
{
    /// <summary>Nothing: a small, smooth force (a weak spring to the origin along x).</summary>
    None,

    /// <summary>Throws <see cref="InvalidOperationException"/> from its evaluation.</summary>
    Throw,

    /// <summary>Writes NaN into one particle's force.</summary>
    NaN,

    /// <summary>Writes +infinity into one particle's force.</summary>
    Infinity,
}

/// <summary>
/// A user force (no Jacobian of its own) that behaves until armed, then fails as told, on its
/// <see cref="AfterEvaluations"/>-th evaluation from the arming on (so that a failure can land in the middle of an
/// integrator's stages or of an implicit solve's finite-difference products).
/// </summary>
internal sealed class FaultyForce : IForceGenerator
{
    public Fault Armed { get; set; }

    public int AfterEvaluations { get; set; }

    public int Particle { get; set; }

    public int Evaluations { get; private set; }

    /// <summary>Every evaluation since the force was made, armed or not.</summary>
    public long TotalEvaluations { get; private set; }

    public void Arm(Fault fault, int afterEvaluations = 0)
    {
        Armed = fault;
        AfterEvaluations = afterEvaluations;
        Evaluations = 0;
    }

    public void AddForces(in ParticleState state, Span<double> forces)
    {
        TotalEvaluations++;
        var x = state.Positions;
        for (var i = 0; i < state.Count; i++)
        {
            forces[3 * i] -= 0.01 * x[3 * i];
        }

        if (Armed == Fault.None || Evaluations++ < AfterEvaluations || Particle >= state.Count)
        {
            return;
        }

        switch (Armed)
        {
            case Fault.Throw:
                throw new InvalidOperationException("FaultyForce: armed to throw.");
            case Fault.NaN:
                forces[(3 * Particle) + 1] = double.NaN;
                break;
            case Fault.Infinity:
                forces[(3 * Particle) + 1] = double.PositiveInfinity;
                break;
        }
    }
}

/// <summary>
/// Linear drag with a Jacobian of its own that throws from <see cref="AddJacobianProduct"/> after a number of products
/// once armed: a failure in the middle of implicit Euler's conjugate gradients.
/// </summary>
internal sealed class FaultyJacobianDrag : IForceGenerator, IForceJacobian
{
    private double _scale;

    public bool Armed { get; set; }

    public int AfterProducts { get; set; }

    public int Products { get; private set; }

    public void Arm(int afterProducts)
    {
        Armed = true;
        AfterProducts = afterProducts;
        Products = 0;
    }

    public void AddForces(in ParticleState state, Span<double> forces)
    {
        var v = state.Velocities;
        for (var k = 0; k < v.Length; k++)
        {
            forces[k] -= 0.05 * v[k];
        }
    }

    public void Linearize(in ParticleState state, double positionScale, double velocityScale, Span<double> positionJacobianTimesVelocity) =>
        _scale = -0.05 * velocityScale;

    public void AddJacobianProduct(ReadOnlySpan<double> w, Span<double> result)
    {
        if (Armed && Products++ >= AfterProducts)
        {
            throw new InvalidOperationException("FaultyJacobianDrag: armed to throw.");
        }

        for (var k = 0; k < w.Length; k++)
        {
            result[k] += _scale * w[k];
        }
    }

    public void AddDiagonalBlocks(Span<double> blocks)
    {
        for (var b = 0; b < blocks.Length; b += 9)
        {
            blocks[b] += _scale;
            blocks[b + 4] += _scale;
            blocks[b + 8] += _scale;
        }
    }
}
