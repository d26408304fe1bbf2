namespace ParticlePhysics.Internal;

/// <summary>
/// A force whose couplings (<see cref="IJacobianCouplings"/>) are only ever appended: no element is removed and no
/// element's particles change, so its pairs are the same as long as its <see cref="IJacobianCouplings.CouplingCount"/>
/// is (the library's spring network, zero-length springs and dampers). A marker beside
/// <see cref="IJacobianCouplings"/> rather than an extension of it, so that this namespace uses nothing of the core.
/// </summary>
internal interface IAppendOnlyCouplings
{
}
