namespace ParticlePhysics.Demo.Cli;

/// <summary>What a numeric option accepts.</summary>
internal enum NumberRule
{
    /// <summary>Any finite number (heights, starting velocities).</summary>
    Finite,

    /// <summary>A finite number &gt;= 0 (stiffness, damping, drag, gravity, rest lengths).</summary>
    NonNegative,

    /// <summary>A positive finite number (masses, dt, duration, sizes, tolerances).</summary>
    Positive,

    /// <summary>A number from 0 to 1 (restitutions).</summary>
    Fraction,
}
