namespace ParticlePhysics.Demo.Cli;

/// <summary>What a numeric option accepts.</summary>
internal enum NumberRule
{
    /// <summary>Any finite number (heights, starting velocities).</summary>
    Finite,

    /// <summary>A finite number &gt;= 0 (stiffness, damping, drag, gravity, rest lengths).</summary>
    NonNegative,

    /// <summary>A positive finite number (dt, duration, sizes).</summary>
    Positive,

    /// <summary>A number from 0 to 1 (restitutions).</summary>
    Fraction,

    /// <summary>A mass: a positive finite number whose inverse is finite too (at least about 5.6e-309 kg).</summary>
    Mass,

    /// <summary>rk45's tolerance: a finite number from <see cref="Integrators.DormandPrince45.MinTolerance"/> up.</summary>
    Tolerance,
}
