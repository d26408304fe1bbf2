namespace ParticlePhysics.Contacts;

/// <summary>
/// The pair filter a contact set hands its broad phase once any particle has a filter of its own: two particles meet
/// when their <see cref="CollisionFilter"/>s accept each other and the user's <see cref="ContactSet.PairFilter"/>, if
/// any, allows them.
/// </summary>
internal sealed class LayeredPairFilter : IContactPairFilter
{
    private CollisionFilter[] _filters = System.Array.Empty<CollisionFilter>();

    /// <summary>The user's filter, consulted after the layers.</summary>
    public IContactPairFilter? Next { get; set; }

    /// <summary>The particles' filters (those beyond the array have the default).</summary>
    public void Use(CollisionFilter[] filters) => _filters = filters;

    /// <inheritdoc />
    public bool MayCollide(int first, int second) =>
        Of(first).Accepts(Of(second)) && (Next is null || Next.MayCollide(first, second));

    private CollisionFilter Of(int particle) => particle < _filters.Length ? _filters[particle] : default;
}
