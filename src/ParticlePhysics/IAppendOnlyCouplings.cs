namespace ParticlePhysics;

/// <summary>
/// A force whose couplings (<see cref="IJacobianCouplings"/>) are only ever appended: no element is removed and no
/// element's particles change, so its pairs are the same as long as its <see cref="IJacobianCouplings.CouplingCount"/>
/// is (the library's spring network, zero-length springs and dampers).
/// </summary>
internal interface IAppendOnlyCouplings : IJacobianCouplings
{
}
