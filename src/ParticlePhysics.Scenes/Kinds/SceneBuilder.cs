using System;
using System.Collections.Generic;
using ParticlePhysics.Aerodynamics;
using ParticlePhysics.Bodies;
using ParticlePhysics.Constraints;
using ParticlePhysics.Contacts;
using ParticlePhysics.Fluids;
using ParticlePhysics.Forces;

namespace ParticlePhysics.Scenes.Kinds;

/// <summary>
/// Builds one world from a scene's objects: the particles in numbering order, then one generator or constraint set per
/// family shared by every object (all springs with a rest length in one <see cref="SpringNetwork"/>, all zero-length
/// springs in one <see cref="ZeroLengthSprings"/>, all rods and cables in one <see cref="RodNetwork"/>, all loads in one
/// <see cref="ConstantLoads"/>), in the order the objects list them. <see cref="Finish"/> adds them to the world in a
/// fixed order, the order the course's scenarios use, so that a scene written like a scenario gives its bits:
/// forces springs, zero-length springs, the cloths' membranes and the bending, loads, drag, the cloths' aerodynamics,
/// gravity (the order a <see cref="Cloth.MeshClothBuilder"/> adds its own in); constraint sets
/// the projections of the springs, membranes and bending (for xpbd), the rods, the cloths' self-collision, the rigid
/// and soft bodies' shape matching, the contacts.
/// </summary>
internal sealed class SceneBuilder
{
    private readonly List<Obstacle> _obstacles = new();
    private SpringNetwork? _springs;
    private ZeroLengthSprings? _linear;
    private RodNetwork? _rods;
    private ConstantLoads? _loads;
    private TriangleMembrane? _membrane;
    private QuadraticBending? _bending;
    private ExcludedPairs? _meshEdges;
    private TriangleAerodynamics? _aerodynamics;
    private readonly List<(int[] Triangles, double Thickness)> _selfCollisions = new();
    private readonly List<(int First, int Count, double Friction, double Restitution)> _solids = new();
    private readonly List<(int First, int Count, double Friction, double RollingFriction)> _grains = new();
    private ShapeMatching? _bodies;
    private readonly List<(FluidParameters Parameters, List<int> Particles)> _fluids = new();

    public SceneBuilder(ParticleWorld world, string file, SceneSettings settings)
    {
        World = world;
        File = file;
        Settings = settings;
    }

    /// <summary>The scene's settings (its air for the cloths' aerodynamics).</summary>
    public SceneSettings Settings { get; }

    /// <summary>The air's drag and lift on the triangles of every cloth with <c>aerodynamics</c>, made on first use.</summary>
    public TriangleAerodynamics Aerodynamics => _aerodynamics ??= new TriangleAerodynamics(World, Settings.NewAir());

    public ParticleWorld World { get; }

    /// <summary>A cloth's self-collision: its triangles (world particle indices) kept <paramref name="thickness"/> apart.</summary>
    public void AddSelfCollision(int[] triangles, double thickness) => _selfCollisions.Add((triangles, thickness));

    /// <summary>The scene file, for errors found while building (a length left out that is not finite).</summary>
    public string File { get; }

    /// <summary>The springs with a rest length (and the dampers of zero-length springs), made on first use.</summary>
    public SpringNetwork Springs => _springs ??= new SpringNetwork(World);

    /// <summary>The zero-rest-length springs, F = -k (x_i - x_j), made on first use.</summary>
    public ZeroLengthSprings LinearSprings => _linear ??= new ZeroLengthSprings(World);

    /// <summary>The rods and cables, made on first use.</summary>
    public RodNetwork Rods => _rods ??= new RodNetwork(World);

    /// <summary>The constant loads, made on first use.</summary>
    public ConstantLoads Loads => _loads ??= new ConstantLoads(World);

    /// <summary>The cloths' membranes, made on first use.</summary>
    public TriangleMembrane Membrane => _membrane ??= new TriangleMembrane(World);

    /// <summary>The cloths' and ropes' bending, made on first use.</summary>
    public QuadraticBending Bending => _bending ??= new QuadraticBending(World);

    /// <summary>The rigid and soft bodies, made on first use.</summary>
    public ShapeMatching Bodies => _bodies ??= new ShapeMatching(World);

    /// <summary>Adds a solid's particles, each of <paramref name="mass"/> and <paramref name="radius"/>; returns the first one's index.</summary>
    public int AddSpheres(Vector3d[] positions, double mass, double radius)
    {
        var first = World.Count;
        foreach (var p in positions)
        {
            World.SetRadius(World.AddParticle(p, mass), radius);
        }

        return first;
    }

    /// <summary>
    /// Notes the particles of a solid (a body, a granular material): they collide with every particle of a radius even
    /// without <c>particleCollisions</c>, with their own friction and restitution (NaN: none of their own).
    /// </summary>
    public void AddSolid(int first, int count, double friction, double restitution) => _solids.Add((first, count, friction, restitution));

    /// <summary>
    /// Notes a block of grains: solids (<see cref="AddSolid"/>) whose friction is both their static and dynamic one,
    /// with a rolling friction (<see cref="ContactSet.SetGranular"/>).
    /// </summary>
    public void AddGranular(int first, int count, double friction, double rollingFriction)
    {
        AddSolid(first, count, friction, double.NaN);
        _grains.Add((first, count, friction, rollingFriction));
    }

    /// <summary>
    /// Notes a block of fluid: <paramref name="count"/> particles from <paramref name="first"/>. Blocks with the same
    /// parameters become one <see cref="PositionBasedFluid"/>, so that two blocks of the same water merge; fluids that
    /// differ are separate sets, which meet only as spheres and only with <c>particleCollisions</c>.
    /// </summary>
    public void AddFluid(FluidParameters parameters, int first, int count)
    {
        var index = _fluids.FindIndex(f => f.Parameters.Equals(parameters));
        if (index < 0)
        {
            _fluids.Add((parameters, new List<int>()));
            index = _fluids.Count - 1;
        }

        for (var i = 0; i < count; i++)
        {
            _fluids[index].Particles.Add(first + i);
        }
    }

    /// <summary>Notes a cloth's mesh edge: its two particles do not collide with each other.</summary>
    public void AddMeshEdge(int first, int second) => (_meshEdges ??= new ExcludedPairs()).Add(first, second);

    /// <summary>How many of each kind of element the objects added ("springs", "rods", ...), for a scene's description.</summary>
    public Dictionary<string, int> Counts { get; } = new();

    /// <summary>Counts <paramref name="count"/> elements of <paramref name="kind"/>.</summary>
    public void Count(string kind, int count) => Counts[kind] = (Counts.TryGetValue(kind, out var n) ? n : 0) + count;

    /// <summary>Adds a collider.</summary>
    public void AddObstacle(Obstacle obstacle) => _obstacles.Add(obstacle);

    /// <summary>Adds the shared generators and sets to the world, then drag, gravity and contacts as the settings say.</summary>
    public ParticleWorld Finish(SceneSettings settings)
    {
        var world = World;
        if (_springs is not null)
        {
            world.AddForce(_springs);
        }

        if (_linear is not null)
        {
            world.AddForce(_linear);
        }

        if (_membrane is not null)
        {
            world.AddForce(_membrane);
        }

        if (_bending is not null)
        {
            world.AddForce(_bending);
        }

        if (_loads is not null)
        {
            world.AddForce(_loads);
        }

        if (settings.Drag > 0)
        {
            world.AddForce(new LinearDrag(settings.Drag));
        }

        if (_aerodynamics is not null)
        {
            world.AddForce(_aerodynamics);
        }

        if (settings.Gravity != Vector3d.Zero)
        {
            world.AddForce(new Gravity(settings.Gravity));
        }

        if (_springs is not null)
        {
            world.AddConstraints(new SpringProjection(_springs));
        }

        if (_linear is not null)
        {
            world.AddConstraints(new SpringProjection(_linear));
        }

        if (_membrane is not null)
        {
            world.AddConstraints(new MembraneProjection(_membrane));
        }

        if (_bending is not null)
        {
            world.AddConstraints(new BendingProjection(_bending));
        }

        if (_rods is not null)
        {
            world.AddConstraints(_rods);
        }

        foreach (var (triangles, thickness) in _selfCollisions)
        {
            world.AddConstraints(new ClothSelfCollision(world, triangles, thickness));
        }

        if (_bodies is not null)
        {
            world.AddConstraints(_bodies);
        }

        var fluids = new List<PositionBasedFluid>();
        foreach (var (parameters, particles) in _fluids)
        {
            var fluid = new PositionBasedFluid(world, parameters.Spacing, parameters.Density)
            {
                Viscosity = parameters.Viscosity,
                Vorticity = parameters.Vorticity,
            };
            fluid.Add(particles.ToArray());
            world.AddConstraints(fluid);
            fluids.Add(fluid);
        }

        if (_obstacles.Count > 0 || settings.ParticleCollisions || _solids.Count > 0)
        {
            var contacts = new ContactSet();
            if (settings.ParticleCollisions || _solids.Count > 0)
            {
                contacts.ParticleCollisions = true;
                contacts.ParticleRestitution = settings.ParticleRestitution;
                contacts.ParticleFriction = settings.ParticleFriction;
                contacts.PairFilter = PairFilter(settings.ParticleCollisions);
            }

            foreach (var obstacle in _obstacles)
            {
                contacts.Add(obstacle);
            }

            foreach (var (first, count, friction, restitution) in _solids)
            {
                if (!double.IsNaN(friction) || !double.IsNaN(restitution))
                {
                    contacts.SetParticleMaterial(first, count, friction, restitution);
                }
            }

            foreach (var (first, count, friction, rolling) in _grains)
            {
                contacts.SetGranular(first, count, friction, rolling);
            }

            // The fluids count the colliders in their densities, and leave pairs of their own particles to themselves.
            foreach (var fluid in fluids)
            {
                fluid.Boundary = contacts;
                fluid.PairFilter.Next = contacts.PairFilter;
                contacts.PairFilter = fluid.PairFilter;
            }

            world.AddConstraints(contacts);
        }

        return world;
    }

    /// <summary>What makes two scene fluids one: their spacing (m), rest density (kg/m^3), XSPH c and vorticity epsilon.</summary>
    public struct FluidParameters : IEquatable<FluidParameters>
    {
        public FluidParameters(double spacing, double density, double viscosity, double vorticity)
        {
            Spacing = spacing;
            Density = density;
            Viscosity = viscosity;
            Vorticity = vorticity;
        }

        public double Spacing { get; }

        public double Density { get; }

        public double Viscosity { get; }

        public double Vorticity { get; }

        public bool Equals(FluidParameters other)
            => Spacing.Equals(other.Spacing) && Density.Equals(other.Density) && Viscosity.Equals(other.Viscosity) && Vorticity.Equals(other.Vorticity);

        public override bool Equals(object? obj) => obj is FluidParameters other && Equals(other);

        public override int GetHashCode() => HashCode.Combine(Spacing, Density, Viscosity, Vorticity);
    }

    // Which pairs of particles collide: not two of one body, not two joined by a spring, rod or mesh edge, and, without
    // particleCollisions, only pairs where one is a solid's.
    private IContactPairFilter? PairFilter(bool everyParticle)
    {
        IContactPairFilter? filter = JoinedPairs();
        if (!everyParticle)
        {
            var solid = new bool[World.Count];
            foreach (var (first, count, _, _) in _solids)
            {
                solid.AsSpan(first, count).Fill(true);
            }

            filter = new SolidPairs(solid, filter);
        }

        if (_bodies is not null)
        {
            _bodies.PairFilter.Next = filter;
            filter = _bodies.PairFilter;
        }

        return filter;
    }

    // The contract: pairs joined by a spring, rod or mesh edge do not collide.
    private ExcludedPairs? JoinedPairs()
    {
        var pairs = _meshEdges ?? new ExcludedPairs();
        var any = _meshEdges is not null;
        if (_springs is not null)
        {
            for (var s = 0; s < _springs.Count; s++)
            {
                var (a, b) = _springs.GetEnds(s);
                pairs.Add(a, b);
                any = true;
            }
        }

        if (_linear is not null)
        {
            for (var s = 0; s < _linear.Count; s++)
            {
                var (a, b) = _linear.GetEnds(s);
                pairs.Add(a, b);
                any = true;
            }
        }

        if (_rods is not null)
        {
            for (var r = 0; r < _rods.Count; r++)
            {
                var (a, b) = _rods.GetEnds(r);
                if (b >= 0)
                {
                    pairs.Add(a, b);
                    any = true;
                }
            }
        }

        return any ? pairs : null;
    }
}
