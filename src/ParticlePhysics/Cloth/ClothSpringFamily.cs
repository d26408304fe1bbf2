namespace ParticlePhysics.Cloth;

/// <summary>
/// One family of a cloth's springs (structural, shear or bend): whether it is built, and the stiffness and axial
/// damping of each of its springs. The rest lengths follow from the grid spacing.
/// </summary>
public sealed class ClothSpringFamily
{
    private double _stiffness;
    private double _damping;

    /// <summary>Creates a family.</summary>
    /// <param name="stiffness">k, in N/m: a finite number &gt;= 0.</param>
    /// <param name="damping">c, in N s/m, along each spring's axis: a finite number &gt;= 0.</param>
    /// <param name="enabled">Whether the family's springs are built.</param>
    public ClothSpringFamily(double stiffness, double damping, bool enabled = true)
    {
        Stiffness = stiffness;
        Damping = damping;
        Enabled = enabled;
    }

    /// <summary>Whether the family's springs are built (default true).</summary>
    public bool Enabled { get; set; }

    /// <summary>k of each spring, in N/m: a finite number &gt;= 0.</summary>
    public double Stiffness
    {
        get => _stiffness;
        set
        {
            Guard.NonNegativeFinite(value, nameof(Stiffness));
            _stiffness = value;
        }
    }

    /// <summary>c of each spring, in N s/m: a finite number &gt;= 0.</summary>
    public double Damping
    {
        get => _damping;
        set
        {
            Guard.NonNegativeFinite(value, nameof(Damping));
            _damping = value;
        }
    }
}
