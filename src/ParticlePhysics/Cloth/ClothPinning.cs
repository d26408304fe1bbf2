namespace ParticlePhysics.Cloth;

/// <summary>Which particles of the cloth are pinned.</summary>
public enum ClothPinning
{
    /// <summary>The two corners of row 0, (0, 0) and (0, n - 1): the course's cloth held by two corners.</summary>
    Corners,

    /// <summary>All of row 0: a curtain.</summary>
    Edge,

    /// <summary>Nothing: the cloth falls freely.</summary>
    None,
}
