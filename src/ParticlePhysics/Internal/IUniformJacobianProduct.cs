namespace ParticlePhysics.Internal;

/// <summary>
/// A linearised force whose Jacobian product is the same multiple of w on every coordinate, result += c w (a drag on
/// every particle), or nothing at all (a uniform field): the world can leave such a term to a solver's own pass over
/// the vectors (<see cref="IJacobianProductTail"/>).
/// </summary>
internal interface IUniformJacobianProduct
{
    /// <summary>
    /// True when the product of the last linearisation is result[k] += c w[k] for every k, with
    /// <paramref name="coefficient"/> c, or leaves result as it is (<paramref name="none"/>); false otherwise.
    /// </summary>
    bool TryGetUniformProduct(out double coefficient, out bool none);
}
