using System;

namespace ParticlePhysics.Benchmarks.Columns;

/// <summary>
/// Says how much cloth work one operation of a benchmark method is, so that <see cref="PerWorkColumn"/> can turn
/// its mean time into time per particle and per spring evaluation. The cloth's n comes from the benchmark's
/// <c>N</c> parameter, or from <see cref="ParticlesPerSide"/> when the class has no such parameter.
/// </summary>
[AttributeUsage(AttributeTargets.Method)]
public sealed class ClothWorkAttribute : Attribute
{
    /// <param name="evaluationsPerOperation">How many times one operation evaluates every spring (RK4 step: 4).</param>
    public ClothWorkAttribute(int evaluationsPerOperation)
    {
        EvaluationsPerOperation = evaluationsPerOperation;
    }

    /// <summary>How many times one operation evaluates every spring of the cloth.</summary>
    public int EvaluationsPerOperation { get; }

    /// <summary>The cloth's n when the benchmark has no <c>N</c> parameter (0: take the parameter).</summary>
    public int ParticlesPerSide { get; set; }
}
