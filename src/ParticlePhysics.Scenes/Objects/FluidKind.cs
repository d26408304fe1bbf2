using System;
using ParticlePhysics.Fluids;
using ParticlePhysics.Scenes.Kinds;

namespace ParticlePhysics.Scenes.Objects;

/// <summary>
/// <c>fluid</c>: a block of liquid held at its rest density by position-based fluids (<see cref="PositionBasedFluid"/>).
/// <c>box</c> {"min", "max"} is filled as a rigid box is, cell centres at min + (i + 1/2) h, x fastest, at
/// <c>spacing</c> h; each particle has mass <c>density</c> h^3 (the rest density, kg/m^3, default 1000) and radius
/// h / 2. <c>viscosity</c> is XSPH's c in [0, 1] (default 0), <c>vorticity</c> the confinement epsilon (default 0).
/// <c>cohesion</c> is accepted only as 0 until surface tension is built, so that a scene asking for it is not run
/// without it.
/// </summary>
internal sealed class FluidKind : ISceneObjectKind
{
    public string Name => "fluid";

    public SceneObject Read(ObjectReader reader, SceneReadContext context)
    {
        var block = LatticeBlock.Read(reader, "fluid", "particle");
        var viscosity = reader.Number("viscosity", 0.0, ValueRule.NonNegative, string.Empty);
        if (viscosity > 1.0)
        {
            throw reader.Error(reader.Get("viscosity")!.Value, reader.PathOf("viscosity"), "must be in [0, 1]: XSPH's c, the fraction of the way to the neighbours' mean velocity per 1/60 s");
        }

        var vorticity = reader.Number("vorticity", 0.0, ValueRule.NonNegative, string.Empty);
        var cohesion = reader.Number("cohesion", 0.0, ValueRule.NonNegative, string.Empty);
        if (cohesion != 0.0)
        {
            throw reader.Error(reader.Get("cohesion")!.Value, reader.PathOf("cohesion"), "must be 0: cohesion and surface tension are not built yet (issue \"fluids\")");
        }

        return new FluidObject(block, new SceneBuilder.FluidParameters(block.Spacing, block.Density, viscosity, vorticity));
    }

    private sealed class FluidObject : SceneObject
    {
        private readonly LatticeBlock _block;
        private readonly SceneBuilder.FluidParameters _fluid;
        private int _first;

        public FluidObject(LatticeBlock block, SceneBuilder.FluidParameters fluid)
        {
            _block = block;
            _fluid = fluid;
        }

        public override int ParticleCount => _block.Positions.Length;

        public override void AddParticles(SceneBuilder builder) => _first = builder.AddSpheres(_block.Positions, _block.Mass, 0.5 * _block.Spacing);

        public override void AddElements(SceneBuilder builder)
        {
            builder.AddFluid(_fluid, _first, _block.Positions.Length);
            builder.Count("fluid particles", _block.Positions.Length);
        }
    }
}
