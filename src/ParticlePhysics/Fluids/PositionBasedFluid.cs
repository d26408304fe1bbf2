using System;
using ParticlePhysics.Bodies;
using ParticlePhysics.Constraints;
using ParticlePhysics.Contacts;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Fluids;

/// <summary>
/// A liquid made of particles, held at its rest density by position-based fluids (Macklin and Müller, "Position Based
/// Fluids", 2013): one density constraint C_i = rho_i / rho_0 - 1 per particle, projected in every xpbd substep, with
/// the artificial pressure against clumping, XSPH viscosity and vorticity confinement on the velocities, and walls that
/// count in the density (<see cref="Boundary"/>).
/// </summary>
/// <remarks>
/// <para>
/// The fluid is filled on a cubic lattice of spacing s (<see cref="AddBox"/>): each particle has mass rho_0 s^3 and
/// radius s / 2 (what colliders and other particles meet), and the smoothing radius is h = 2 s (26 neighbours at
/// rest). The density is rho_i = kappa sum_j m_j W(x_i - x_j) with spiky (<see cref="SphKernel"/>, which says why one
/// kernel serves densities and gradients), and kappa is fixed so that the rest lattice is exactly at rho_0: spiky's
/// sum over a lattice at h = 2 s is 1.236 / s^3, not 1 / s^3, and without kappa a block would start 24 % compressed.
/// </para>
/// <para>
/// The constraint is one-sided, C_i = max(rho_i / rho_0 - 1, 0): a particle with too few neighbours (at the free
/// surface, in a splash) is not pulled towards others. For particles of any masses the projection of every
/// constraint moves particle a by dx_a = w_a (kappa / rho_0) sum_b (lambda_a m_b + lambda_b m_a + s_corr (m_a + m_b) / 2) grad_a W_ab,
/// lambda_a = -C_a / (sum_k w_k |grad_k C_a|^2 + epsilon D_0), the pair's weight symmetric so that each pair's
/// moves m_a dx_a + m_b dx_b sum to 0: the projection keeps the momentum. For equal masses this is the paper's
/// dx_i = (1 / rho_0) sum_j (lambda_i + lambda_j + s_corr) grad W_ij. D_0 is the denominator of a particle of the
/// rest lattice, so the relaxation epsilon (<see cref="Relaxation"/>) is a fraction of it, and the artificial pressure
/// s_corr = -k (W(r) / W(dq))^n / D_0 is the push a density error of k (W / W(dq))^n would give
/// (<see cref="ArtificialPressure"/>): both dimensionless, whatever the spacing and the density.
/// </para>
/// <para>
/// Walls, bodies and cloth meet the fluid through the contact stage (a <see cref="ContactSet"/> added after this set),
/// by the particles' radii; the obstacles of the contact set given as <see cref="Boundary"/> also count in the density,
/// so that the fluid is not drawn into them. Pinned fluid particles count in the density and do not move, so they
/// make walls too. Give the contact set <see cref="PairFilter"/>, so that two fluid particles leave each other to
/// this set. Neighbours are found once per substep in cells of side h, in the contact stage's cell table
/// (<see cref="CellBuckets"/>); nothing is allocated per step once the buffers have grown to the fluid. Under a force-based integrator the end of the step is projected once, and
/// each correction dx changes its particle's velocity by dx / dt.
/// </para>
/// </remarks>
public sealed partial class PositionBasedFluid : IConstraintSet
{
    /// <summary>The smoothing radius over the spacing, h / s.</summary>
    public const double SmoothingRatio = 2.0;

    /// <summary>The default <see cref="Relaxation"/>.</summary>
    public const double DefaultRelaxation = 2.0;

    /// <summary>The default <see cref="ArtificialPressure"/> k.</summary>
    public const double DefaultArtificialPressure = 0.0;

    private readonly ParticleWorld _world;
    private readonly SphKernel _kernel;
    private readonly double _kappa;
    private readonly double _restDenominator;
    private readonly double _pressurePeak; // W(dq) with dq = 0.2 h
    private double _relaxation = DefaultRelaxation;
    private double _artificialPressure = DefaultArtificialPressure;
    private double _viscosity;
    private double _vorticity;
    private int _iterations = 1;
    private int[] _particles = Array.Empty<int>();
    private int[] _localOf = Array.Empty<int>();
    private int _count;
    private int _maxIndex = -1;

    /// <summary>
    /// An empty fluid of rest density <paramref name="restDensity"/> (kg/m^3) whose particles are
    /// <paramref name="spacing"/> (m) apart at rest; add it with <see cref="ParticleWorld.AddConstraints"/>, before the
    /// contact set.
    /// </summary>
    /// <exception cref="ArgumentOutOfRangeException">The spacing or the density is not positive and finite.</exception>
    public PositionBasedFluid(ParticleWorld world, double spacing, double restDensity)
    {
        Guard.NotNull(world, nameof(world));
        Guard.PositiveFinite(spacing, nameof(spacing));
        Guard.PositiveFinite(restDensity, nameof(restDensity));
        _world = world;
        Spacing = spacing;
        RestDensity = restDensity;
        _kernel = new SphKernel(SmoothingRatio * spacing);
        ParticleMass = restDensity * spacing * spacing * spacing;
        Guard.PositiveWithFiniteInverse(ParticleMass, nameof(restDensity), "kg (the particle mass rho_0 s^3)");
        (_kappa, _restDenominator) = RestLattice(_kernel, spacing, restDensity, ParticleMass);
        _pressurePeak = _kernel.Density(0.2 * _kernel.Radius);
        PairFilter = new FluidPairFilter(this);
        _wall = new FluidWall(_kernel, spacing, ParticleMass);
    }

    /// <summary>The spacing s of the rest lattice, m.</summary>
    public double Spacing { get; }

    /// <summary>The rest density rho_0, kg/m^3.</summary>
    public double RestDensity { get; }

    /// <summary>The mass of a particle of <see cref="AddBox"/>, rho_0 s^3, kg.</summary>
    public double ParticleMass { get; }

    /// <summary>The smoothing radius h = 2 s, m.</summary>
    public double SmoothingRadius => _kernel.Radius;

    /// <summary>The number of fluid particles.</summary>
    public int Count => _count;

    /// <summary>The world's indices of the fluid particles, in the order they were added.</summary>
    public ReadOnlySpan<int> Particles => _particles.AsSpan(0, _count);

    /// <summary>The filter that leaves two fluid particles to this set: set it as the contact set's pair filter.</summary>
    public FluidPairFilter PairFilter { get; }

    /// <summary>
    /// The relaxation epsilon of lambda's denominator, as a fraction of a rest particle's (dimensionless, default 2):
    /// the projection's largest step on the rest lattice is 2.82 / (1 + epsilon) times what makes that pattern's
    /// density exact (<see cref="SphKernel"/>), and above 2 it would overshoot and grow; at 2 it is 0.94. Smaller is
    /// stiffer per substep and rings; larger is softer (more substeps make it stiff again).
    /// </summary>
    /// <exception cref="ArgumentOutOfRangeException">The value is negative or not finite.</exception>
    public double Relaxation
    {
        get => _relaxation;
        set
        {
            Guard.NonNegativeFinite(value, nameof(value));
            _relaxation = value;
        }
    }

    /// <summary>
    /// The artificial pressure k of s_corr = -k (W(r) / W(0.2 h))^4, as a density error (dimensionless): a
    /// short-range repulsion that keeps particles from clumping. Off by default until it is tuned against the dam break.
    /// </summary>
    /// <exception cref="ArgumentOutOfRangeException">The value is negative or not finite.</exception>
    public double ArtificialPressure
    {
        get => _artificialPressure;
        set
        {
            Guard.NonNegativeFinite(value, nameof(value));
            _artificialPressure = value;
        }
    }

    /// <summary>
    /// XSPH's c (dimensionless, default 0): each particle's velocity moves the fraction c of the way to its neighbours'
    /// kernel-weighted mean per 1/60 s, as the paper applies it once per 60 Hz frame; a substep of length dt applies
    /// c dt / (1/60 s), so the viscosity does not depend on the number of substeps.
    /// </summary>
    /// <exception cref="ArgumentOutOfRangeException">The value is negative, not finite, or above 1.</exception>
    public double Viscosity
    {
        get => _viscosity;
        set
        {
            Guard.NonNegativeFinite(value, nameof(value));
            if (value > 1.0)
            {
                throw new ArgumentOutOfRangeException(nameof(value), value, $"the XSPH viscosity c must be in [0, 1]; got {Guard.Format(value)}.");
            }

            _viscosity = value;
        }
    }

    /// <summary>
    /// The vorticity confinement epsilon (dimensionless, default 0): a particle of vorticity omega is pushed along
    /// N x omega with an acceleration of epsilon times the centripetal acceleration |omega|^2 h of a vortex of the
    /// kernel's size, N the unit gradient of |omega| (Fedkiw, Stam and Jensen 2001, as in the paper): it gives back
    /// the swirls that the projection and XSPH damp.
    /// </summary>
    /// <exception cref="ArgumentOutOfRangeException">The value is negative or not finite.</exception>
    public double Vorticity
    {
        get => _vorticity;
        set
        {
            Guard.NonNegativeFinite(value, nameof(value));
            _vorticity = value;
        }
    }

    /// <summary>The projections of the density constraints per substep (default 1: xpbd's substeps are the iterations).</summary>
    /// <exception cref="ArgumentOutOfRangeException">The value is not 1 to 100.</exception>
    public int Iterations
    {
        get => _iterations;
        set
        {
            if (value < 1 || value > 100)
            {
                throw new ArgumentOutOfRangeException(nameof(value), value, $"iterations must be 1 to 100; got {value}.");
            }

            _iterations = value;
        }
    }

    /// <summary>
    /// Adds the world's particles listed to the fluid (their masses and radii stay as they are: give them
    /// <see cref="ParticleMass"/> and s / 2 to be at the rest density on the rest lattice).
    /// </summary>
    /// <exception cref="ArgumentException">An index is outside the world, listed twice, or already in the fluid.</exception>
    public void Add(ReadOnlySpan<int> particles)
    {
        var indices = particles.ForReading();
        var count = _world.Count;
        for (var k = 0; k < indices.Length; k++)
        {
            Guard.ParticleIndex(indices[k], count, nameof(particles));
            if (IsFluid(indices[k]))
            {
                throw new ArgumentException($"particle {indices[k]} is already in the fluid.", nameof(particles));
            }
        }

        Guard.NoDuplicateParticles(particles, nameof(particles));
        Reserve(_count + indices.Length, count);
        for (var k = 0; k < indices.Length; k++)
        {
            _localOf[indices[k]] = _count;
            _maxIndex = Math.Max(_maxIndex, indices[k]);
            _particles[_count++] = indices[k];
        }
    }

    /// <summary>
    /// Fills the box from <paramref name="min"/> to <paramref name="max"/> with fluid at rest, as a rigid box is filled
    /// (<see cref="BodyLattice.Box"/>: cell centres at the spacing, x fastest), each particle of mass
    /// <see cref="ParticleMass"/> and radius s / 2. Returns the world index of the first; they are consecutive.
    /// </summary>
    /// <exception cref="ArgumentException">The box is empty or not finite, or holds more particles than the world can take.</exception>
    public int AddBox(Vector3d min, Vector3d max)
    {
        Guard.Finite(min, nameof(min));
        Guard.Finite(max, nameof(max));
        var positions = BodyLattice.Box(0.5 * (min + max), max - min, Rotation3d.Identity, Spacing);
        var first = _world.Count;
        if ((long)first + positions.Length > ParticleWorld.MaxParticles)
        {
            throw new ArgumentException($"the box holds {positions.Length} particles; the world has {first} of at most {ParticleWorld.MaxParticles}.", nameof(max));
        }

        var indices = new int[positions.Length];
        for (var k = 0; k < positions.Length; k++)
        {
            indices[k] = _world.AddParticle(positions[k], ParticleMass);
            _world.SetRadius(indices[k], 0.5 * Spacing);
        }

        Add(indices);
        return first;
    }

    /// <summary>Whether world particle <paramref name="particle"/> is in the fluid.</summary>
    public bool IsFluid(int particle) => (uint)particle < (uint)_localOf.Length && _localOf[particle] >= 0;

    /// <inheritdoc />
    public void Project(in ConstraintContext context)
    {
        CheckContext(in context);
        FindNeighbours(in context);
        ProjectDensities(in context);
    }

    /// <inheritdoc />
    public void SolveVelocities(in ConstraintContext context)
    {
        CheckContext(in context);
        CorrectVelocities(in context);
    }

    /// <inheritdoc />
    public void Resolve(in ConstraintContext context)
    {
        CheckContext(in context);
        FindNeighbours(in context);
        SaveGathered();
        ProjectDensities(in context);
        ChangeVelocitiesByMoves(in context);
        CorrectVelocities(in context);
    }

    // The rest lattice's kappa (so that a particle with all 26 neighbours at spacing s is at rho_0) and its lambda
    // denominator D_0 = (kappa / rho_0)^2 m sum_b |grad W_b|^2 (sum_b grad W_b = 0 by symmetry).
    private static (double Kappa, double Denominator) RestLattice(SphKernel kernel, double spacing, double density, double mass)
    {
        var reach = (int)SmoothingRatio + 1;
        double sum = 0.0, squares = 0.0;
        for (var z = -reach; z <= reach; z++)
        {
            for (var y = -reach; y <= reach; y++)
            {
                for (var x = -reach; x <= reach; x++)
                {
                    var r2 = spacing * spacing * ((x * x) + (y * y) + (z * z));
                    var r = Math.Sqrt(r2);
                    sum += kernel.Density(r);
                    var g = kernel.GradientOverDistance(r);
                    squares += g * g * r2;
                }
            }
        }

        var kappa = density / (mass * sum);
        var scale = kappa / density;
        return (kappa, scale * scale * mass * squares);
    }

    private void CheckContext(in ConstraintContext context)
    {
        if (_maxIndex >= context.Count)
        {
            throw new InvalidOperationException($"the fluid holds particle {_maxIndex}, but the context has {context.Count} particles.");
        }
    }
}
