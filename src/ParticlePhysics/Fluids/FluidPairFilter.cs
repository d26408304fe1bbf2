using ParticlePhysics.Contacts;

namespace ParticlePhysics.Fluids;

/// <summary>
/// The contact pair filter of a <see cref="PositionBasedFluid"/>: two fluid particles never collide as spheres (their
/// density constraints keep them apart), everything else is left to <see cref="Next"/> (every pair when it is null).
/// </summary>
public sealed class FluidPairFilter : IContactPairFilter
{
    private readonly PositionBasedFluid _fluid;

    internal FluidPairFilter(PositionBasedFluid fluid)
    {
        _fluid = fluid;
    }

    /// <summary>The filter asked about the other pairs (a body's <see cref="Bodies.BodyPairFilter"/>), or null.</summary>
    public IContactPairFilter? Next { get; set; }

    /// <inheritdoc />
    public bool MayCollide(int first, int second)
    {
        if (_fluid.IsFluid(first) && _fluid.IsFluid(second))
        {
            return false;
        }

        return Next is null || Next.MayCollide(first, second);
    }
}
