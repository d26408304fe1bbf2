using System;
using System.Collections.Generic;
using ParticlePhysics.Aerodynamics;
using ParticlePhysics.Constraints;
using ParticlePhysics.Forces;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Cloth;

/// <summary>How a mesh cloth resists stretching.</summary>
public enum ClothStretch
{
    /// <summary>A constant-strain triangle membrane of modulus Y and Poisson's ratio nu (<see cref="TriangleMembrane"/>).</summary>
    Membrane,

    /// <summary>A spring of stiffness k on every edge of the mesh (<see cref="SpringNetwork"/>).</summary>
    EdgeSprings,

    /// <summary>Nothing but the springs added with <see cref="MeshClothBuilder.AddSpring(int, int, double, double)"/>.</summary>
    None,
}

/// <summary>How a mesh cloth's mass is spread over its particles.</summary>
public enum ClothMassDistribution
{
    /// <summary>Each triangle gives a third of its mass to each of its corners (the mass of a lumped finite element).</summary>
    LumpedByArea,

    /// <summary>Every particle the same mass, as <see cref="ClothBuilder"/>'s grids have.</summary>
    Uniform,
}

/// <summary>
/// Builds a cloth from any triangle mesh (<see cref="WeldedMesh"/>: a flag, a cape, a curtain with a hole, a sail): its
/// particles at the mesh's welded vertices with lumped masses, stretch as a membrane (physical Y in N/m and nu) or as
/// springs on the edges, plate bending of rigidity D in N m (<see cref="PlateBending"/>), pins by vertex, linear drag,
/// and the projections that step it under xpbd.
/// </summary>
/// <remarks>
/// The forces, in the order they are added: the springs (edge springs, then those of <see cref="AddSpring(int, int, double, double)"/>), the
/// membrane, the bending, linear drag, the aerodynamics (with an <see cref="Air"/>), and (<see cref="Build"/> only) gravity; then the constraint sets projecting the
/// springs, the membrane and the bending under xpbd (they do nothing under the force-based integrators). Each is made
/// only when the cloth has some of it. The membrane and the bending are measured against their theories in the tests
/// (a strip's stretch F / (Y b), a cantilever's sag rho_A g L^4 / (8 D), a cylinder's energy D A / (2 R^2)), so that
/// refining the mesh keeps the material.
/// </remarks>
public sealed class MeshClothBuilder
{
    private readonly List<int> _pins = new();
    private readonly List<(int A, int B, double K, double C, double L)> _springs = new();
    private double _mass = 1.0;
    private double? _density;
    private double _modulus = 1000.0, _poisson = 0.3, _membraneDamping = 0.1;
    private double _springStiffness = 50.0, _springDamping = 0.05;
    private double _rigidity;
    private double _drag = 0.0;
    private double _gravity = Forces.Gravity.StandardAcceleration;
    private ClothStretch _stretch = ClothStretch.Membrane;
    private ClothMassDistribution _distribution = ClothMassDistribution.LumpedByArea;

    /// <summary>A builder for a cloth of <paramref name="mesh"/>.</summary>
    public MeshClothBuilder(WeldedMesh mesh)
    {
        Guard.NotNull(mesh, nameof(mesh));
        Mesh = mesh;
    }

    /// <summary>The mesh, welded.</summary>
    public WeldedMesh Mesh { get; }

    /// <summary>The total mass, in kg (default 1); setting it forgets <see cref="AreaDensity"/>.</summary>
    public double TotalMass
    {
        get => _density is { } density ? density * TotalArea : _mass;
        set
        {
            Guard.Mass(value, nameof(TotalMass));
            _mass = value;
            _density = null;
        }
    }

    /// <summary>The mass per area, in kg/m^2 (default: <see cref="TotalMass"/> over the area); setting it overrides the total mass.</summary>
    public double AreaDensity
    {
        get => _density ?? (_mass / TotalArea);
        set
        {
            Guard.PositiveFinite(value, nameof(AreaDensity));
            _density = value;
        }
    }

    /// <summary>The mesh's area as given, m^2.</summary>
    public double TotalArea
    {
        get
        {
            var area = 0.0;
            for (var t = 0; t < Mesh.TriangleCount; t++)
            {
                area += Mesh.TriangleArea(t);
            }

            return area;
        }
    }

    /// <summary>How the mass is spread (default <see cref="ClothMassDistribution.LumpedByArea"/>).</summary>
    public ClothMassDistribution MassDistribution
    {
        get => _distribution;
        set
        {
            if (value is not (ClothMassDistribution.LumpedByArea or ClothMassDistribution.Uniform))
            {
                throw new ArgumentOutOfRangeException(nameof(MassDistribution), value, "MassDistribution must be LumpedByArea or Uniform.");
            }

            _distribution = value;
        }
    }

    /// <summary>How the cloth resists stretching (default <see cref="ClothStretch.Membrane"/>).</summary>
    public ClothStretch Stretch
    {
        get => _stretch;
        set
        {
            if (value is not (ClothStretch.Membrane or ClothStretch.EdgeSprings or ClothStretch.None))
            {
                throw new ArgumentOutOfRangeException(nameof(Stretch), value, "Stretch must be Membrane, EdgeSprings or None.");
            }

            _stretch = value;
        }
    }

    /// <summary>The membrane's Y, Young's modulus times thickness, in N/m (default 1000).</summary>
    public double Modulus
    {
        get => _modulus;
        set
        {
            Guard.PositiveFinite(value, nameof(Modulus));
            _modulus = value;
        }
    }

    /// <summary>The membrane's Poisson's ratio nu, 0 to less than 0.5 (default 0.3).</summary>
    public double Poisson
    {
        get => _poisson;
        set
        {
            if (!(value >= 0.0 && value < 0.5))
            {
                throw new ArgumentOutOfRangeException(nameof(Poisson), value, $"Poisson must be from 0 to less than 0.5; got {Guard.Format(value)}.");
            }

            _poisson = value;
        }
    }

    /// <summary>The membrane's viscosity eta, N s/m (default 0.1): the stress eta / Y times the elastic law of the strain rate.</summary>
    public double MembraneDamping
    {
        get => _membraneDamping;
        set
        {
            Guard.NonNegativeFinite(value, nameof(MembraneDamping));
            _membraneDamping = value;
        }
    }

    /// <summary>The edge springs' stiffness k, N/m (default 50), for <see cref="ClothStretch.EdgeSprings"/>.</summary>
    public double SpringStiffness
    {
        get => _springStiffness;
        set
        {
            Guard.NonNegativeFinite(value, nameof(SpringStiffness));
            _springStiffness = value;
        }
    }

    /// <summary>The edge springs' axial damping c, N s/m (default 0.05).</summary>
    public double SpringDamping
    {
        get => _springDamping;
        set
        {
            Guard.NonNegativeFinite(value, nameof(SpringDamping));
            _springDamping = value;
        }
    }

    /// <summary>The plate's flexural rigidity D, N m (default 0: no bending). For a shell of thickness t, Y t^2 / 12 / (1 - nu^2).</summary>
    public double BendingRigidity
    {
        get => _rigidity;
        set
        {
            Guard.NonNegativeFinite(value, nameof(BendingRigidity));
            _rigidity = value;
        }
    }

    /// <summary>
    /// The linear drag lambda on every particle of the cloth, N s/m (default 0). Per particle, so the same value damps a
    /// finer mesh more, and xpbd and the explicit integrators take it explicitly (stable while h lambda / m &lt; 2 for the
    /// lightest particle): prefer the membrane's damping, which is a material's.
    /// </summary>
    public double Drag
    {
        get => _drag;
        set
        {
            Guard.NonNegativeFinite(value, nameof(Drag));
            _drag = value;
        }
    }

    /// <summary>
    /// The air whose drag and lift act on every triangle (<see cref="TriangleAerodynamics"/>), or null for none (the
    /// default). The cloth keeps this object: change its wind between steps and the cloth feels it.
    /// </summary>
    public Air? Air { get; set; }

    /// <summary>g, in m/s^2, pointing down -y (default 9.81); used by <see cref="Build"/> only.</summary>
    public double Gravity
    {
        get => _gravity;
        set
        {
            Guard.NonNegativeFinite(value, nameof(Gravity));
            _gravity = value;
        }
    }

    /// <summary>The render vertices pinned (their particles are; a seam's vertices share one).</summary>
    public IReadOnlyList<int> Pins => _pins;

    /// <summary>Pins the particle of render vertex <paramref name="vertex"/>.</summary>
    /// <returns>This builder.</returns>
    public MeshClothBuilder Pin(int vertex)
    {
        Guard.ParticleIndex(vertex, Mesh.VertexCount, nameof(vertex));
        _pins.Add(vertex);
        return this;
    }

    /// <summary>Pins the particles of every render vertex listed.</summary>
    /// <returns>This builder.</returns>
    public MeshClothBuilder PinVertices(ReadOnlySpan<int> vertices)
    {
        var list = vertices.ToArray();
        foreach (var v in list)
        {
            Guard.ParticleIndex(v, Mesh.VertexCount, nameof(vertices));
        }

        _pins.AddRange(list);
        return this;
    }

    /// <summary>
    /// Adds a spring between the particles of two render vertices, of rest length their distance in the mesh (any pair:
    /// a grid's shear and bend springs, a tether).
    /// </summary>
    /// <returns>This builder.</returns>
    public MeshClothBuilder AddSpring(int vertexA, int vertexB, double stiffness, double damping) =>
        AddSpring(vertexA, vertexB, stiffness, damping, double.NaN);

    /// <summary>Adds a spring between the particles of two render vertices, of the given rest length (m, finite and &gt;= 0).</summary>
    /// <returns>This builder.</returns>
    public MeshClothBuilder AddSpring(int vertexA, int vertexB, double stiffness, double damping, double restLength)
    {
        if (!double.IsNaN(restLength))
        {
            Guard.NonNegativeFinite(restLength, nameof(restLength));
        }

        Guard.ParticleIndex(vertexA, Mesh.VertexCount, nameof(vertexA));
        Guard.ParticleIndex(vertexB, Mesh.VertexCount, nameof(vertexB));
        if (Mesh.ParticleOf(vertexA) == Mesh.ParticleOf(vertexB))
        {
            throw new ArgumentException($"Vertices {vertexA} and {vertexB} are one particle: a spring needs two.", nameof(vertexB));
        }

        Guard.NonNegativeFinite(stiffness, nameof(stiffness));
        Guard.NonNegativeFinite(damping, nameof(damping));
        _springs.Add((vertexA, vertexB, stiffness, damping, restLength));
        return this;
    }

    /// <summary>Each particle's mass, in kg, as the cloth will have it.</summary>
    public double[] ParticleMasses()
    {
        var n = Mesh.ParticleCount;
        var masses = new double[n];
        var density = AreaDensity;
        if (_distribution == ClothMassDistribution.Uniform)
        {
            var each = TotalMass / n;
            masses.AsSpan().Fill(each);
            return masses;
        }

        var triangles = Mesh.ParticleTriangles.ForReading();
        for (var t = 0; t < Mesh.TriangleCount; t++)
        {
            var third = density * Mesh.TriangleArea(t) / 3.0;
            masses[triangles[3 * t]] += third;
            masses[triangles[(3 * t) + 1]] += third;
            masses[triangles[(3 * t) + 2]] += third;
        }

        return masses;
    }

    /// <summary>
    /// Builds the cloth alone in a new world: its particles, its springs, membrane and bending, linear drag and gravity,
    /// in that order, then their projections for xpbd.
    /// </summary>
    /// <exception cref="InvalidOperationException">A particle's mass too small to have a finite inverse.</exception>
    public TriangleCloth Build()
    {
        var masses = Validate(0);
        var world = new ParticleWorld(Mesh.ParticleCount);
        return Add(world, masses, addGravity: true);
    }

    /// <summary>
    /// Adds the cloth to a world that may hold other bodies: its particles after the existing ones, its forces (linear
    /// drag on its own particles; no gravity: add one <see cref="Forces.Gravity"/> per world) and their projections.
    /// Everything is checked first: a rejected call leaves the world as it was.
    /// </summary>
    /// <exception cref="InvalidOperationException">A particle's mass too small to have a finite inverse, or more particles than the world can take.</exception>
    public TriangleCloth AddTo(ParticleWorld world)
    {
        Guard.NotNull(world, nameof(world));
        world.ThrowIfStepping();
        var masses = Validate(world.Count);
        return Add(world, masses, addGravity: false);
    }

    /// <summary>
    /// Adds only the particles (for hosts that share one generator per family between bodies: the scene loader), with
    /// their masses, the given velocities (one per particle, or empty for rest) and pins. Returns the world's index of
    /// the cloth's particle 0.
    /// </summary>
    public int AddParticles(ParticleWorld world, ReadOnlySpan<Vector3d> velocities)
    {
        Guard.NotNull(world, nameof(world));
        world.ThrowIfStepping();
        if (velocities.Length != 0 && velocities.Length != Mesh.ParticleCount)
        {
            throw new ArgumentException($"velocities must hold one per particle ({Mesh.ParticleCount}) or none; it holds {velocities.Length}.", nameof(velocities));
        }

        var masses = Validate(world.Count);
        return AddParticles(world, masses, velocities.ToArray());
    }

    /// <summary>
    /// Adds the cloth's elements for particles from <paramref name="firstParticle"/> on, into the given generators (null
    /// for a family the cloth does not need: springs only for <see cref="ClothStretch.EdgeSprings"/> or
    /// <see cref="AddSpring(int, int, double, double)"/>, the membrane for <see cref="ClothStretch.Membrane"/>, the bending when D &gt; 0).
    /// </summary>
    public void AddElements(int firstParticle, SpringNetwork? springs, TriangleMembrane? membrane, QuadraticBending? bending)
    {
        if (NeedsSprings)
        {
            Guard.NotNull(springs, nameof(springs));
            AddSprings(springs!, firstParticle);
        }

        if (_stretch == ClothStretch.Membrane)
        {
            Guard.NotNull(membrane, nameof(membrane));
            var triangles = Mesh.ParticleTriangles.ForReading();
            for (var t = 0; t < Mesh.TriangleCount; t++)
            {
                int a = triangles[3 * t], b = triangles[(3 * t) + 1], c = triangles[(3 * t) + 2];
                membrane!.Add(
                    firstParticle + a, firstParticle + b, firstParticle + c, Mesh.ParticlePosition(a), Mesh.ParticlePosition(b), Mesh.ParticlePosition(c), _modulus, _poisson, _membraneDamping);
            }
        }

        if (_rigidity > 0.0)
        {
            Guard.NotNull(bending, nameof(bending));
            PlateBending.AddSheet(bending!, Mesh.ParticleTriangles, Mesh.ParticlePositions, firstParticle, _rigidity);
        }
    }

    /// <summary>
    /// Adds the mesh's triangles, for particles from <paramref name="firstParticle"/> on, to
    /// <paramref name="aerodynamics"/> (for hosts that share one generator between cloths: the scene loader).
    /// </summary>
    public void AddTriangles(int firstParticle, TriangleAerodynamics aerodynamics)
    {
        Guard.NotNull(aerodynamics, nameof(aerodynamics));
        var triangles = Mesh.ParticleTriangles.ForReading();
        for (var t = 0; t < Mesh.TriangleCount; t++)
        {
            aerodynamics.Add(firstParticle + triangles[3 * t], firstParticle + triangles[(3 * t) + 1], firstParticle + triangles[(3 * t) + 2]);
        }
    }

    /// <summary>Whether the cloth has springs: edge springs, or springs added one by one.</summary>
    public bool NeedsSprings => _stretch == ClothStretch.EdgeSprings || _springs.Count > 0;

    private TriangleCloth Add(ParticleWorld world, double[] masses, bool addGravity)
    {
        var first = AddParticles(world, masses, Array.Empty<Vector3d>());
        var springs = NeedsSprings ? new SpringNetwork(world) : null;
        var membrane = _stretch == ClothStretch.Membrane ? new TriangleMembrane(world) : null;
        var bending = _rigidity > 0.0 ? new QuadraticBending(world) : null;
        AddElements(first, springs, membrane, bending);
        var particles = new int[Mesh.ParticleCount];
        for (var i = 0; i < particles.Length; i++)
        {
            particles[i] = first + i;
        }

        var drag = addGravity ? new LinearDrag(_drag) : new LinearDrag(_drag, world, particles);
        var gravity = addGravity ? Forces.Gravity.Down(_gravity) : null;
        if (springs is not null)
        {
            world.AddForce(springs);
        }

        if (membrane is not null)
        {
            world.AddForce(membrane);
        }

        if (bending is not null)
        {
            world.AddForce(bending);
        }

        world.AddForce(drag);
        TriangleAerodynamics? aerodynamics = null;
        if (Air is { } air)
        {
            aerodynamics = new TriangleAerodynamics(world, air);
            AddTriangles(first, aerodynamics);
            world.AddForce(aerodynamics);
        }

        if (gravity is not null)
        {
            world.AddForce(gravity);
        }

        var springProjection = springs is null ? null : new SpringProjection(springs);
        var membraneProjection = membrane is null ? null : new MembraneProjection(membrane);
        var bendingProjection = bending is null ? null : new BendingProjection(bending);
        if (springProjection is not null)
        {
            world.AddConstraints(springProjection);
        }

        if (membraneProjection is not null)
        {
            world.AddConstraints(membraneProjection);
        }

        if (bendingProjection is not null)
        {
            world.AddConstraints(bendingProjection);
        }

        return new TriangleCloth(world, Mesh, first, springs, springProjection, membrane, membraneProjection, bending, bendingProjection, drag, aerodynamics, gravity);
    }

    private int AddParticles(ParticleWorld world, double[] masses, Vector3d[] velocities)
    {
        var first = world.Count;
        for (var i = 0; i < masses.Length; i++)
        {
            world.AddParticle(Mesh.ParticlePosition(i), velocities.Length == 0 ? Vector3d.Zero : velocities[i], masses[i]);
        }

        foreach (var vertex in _pins)
        {
            var i = first + Mesh.ParticleOf(vertex);
            if (!world.IsPinned(i))
            {
                world.Pin(i, world.GetVelocity(i));
            }
        }

        return first;
    }

    private void AddSprings(SpringNetwork springs, int first)
    {
        var particleOf = Mesh.ParticleOfVertex.ForReading();
        if (_stretch == ClothStretch.EdgeSprings)
        {
            // Every edge once, in the order the triangles first name it.
            var seen = new HashSet<long>();
            var triangles = Mesh.ParticleTriangles.ForReading();
            for (var t = 0; t < Mesh.TriangleCount; t++)
            {
                for (var e = 0; e < 3; e++)
                {
                    int a = triangles[(3 * t) + e], b = triangles[(3 * t) + ((e + 1) % 3)];
                    var key = a < b ? ((long)a << 32) | (uint)b : ((long)b << 32) | (uint)a;
                    if (seen.Add(key))
                    {
                        var rest = (Mesh.ParticlePosition(a) - Mesh.ParticlePosition(b)).Length;
                        springs.Add(first + a, first + b, _springStiffness, rest, _springDamping);
                    }
                }
            }
        }

        foreach (var (a, b, k, c, l) in _springs)
        {
            int i = particleOf[a], j = particleOf[b];
            springs.Add(first + i, first + j, k, double.IsNaN(l) ? (Mesh.ParticlePosition(i) - Mesh.ParticlePosition(j)).Length : l, c);
        }
    }

    /// <summary>The masses, checked, and the world's room for the particles.</summary>
    private double[] Validate(int existing)
    {
        if (existing > ParticleWorld.MaxParticles - Mesh.ParticleCount)
        {
            throw new InvalidOperationException(
                $"The world holds {existing} particles; {Mesh.ParticleCount} more would pass its limit of {ParticleWorld.MaxParticles}.");
        }

        var masses = ParticleMasses();
        for (var i = 0; i < masses.Length; i++)
        {
            if (!DoubleChecks.IsFinite(masses[i]) || !(masses[i] >= Guard.SmallestMass))
            {
                throw new InvalidOperationException(
                    $"Particle {i} of the cloth would have mass {Guard.Format(masses[i])} kg: every particle needs a positive mass with a finite inverse "
                    + $"(at least {Guard.Format(Guard.SmallestMass)} kg); give the cloth more mass.");
            }
        }

        return masses;
    }
}
